// core/tree_solver.cpp: O(n) factor and solve in frontier order (PAPER.md §3 steps 2 and 3).
//
// The per-block work is a handful of small dense operations whose sizes follow from the block
// kind: a node has 6 rows, an edge r = 1..6, an edge's parent is a node. The kernels below are
// templates on those sizes (one switch per block picks the instance), so they compile to
// unrolled fixed-size code. Symmetric pivots are kept as their lower triangle only.
//
// Memory: at large n the sweeps are bound by memory, not arithmetic. Layout order makes a
// block's own data (its factors, its node/edge neighbour) sequential; what is not sequential is
// the parent-side block of an edge (anywhere later in the layout for a branching tree) and the
// body/joint-indexed inputs and outputs. Those are prefetched a few blocks ahead.
#include "core/tree_solver.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace frontier::core
{

namespace
{

// In-place lower Cholesky of the N x N column-major matrix a (only its lower triangle is read).
// The factor's diagonal is stored as reciprocals 1 / l_jj. Returns false when a pivot falls below
// cRelativePivot times its own row's diagonal entry (cancellation: dependent rows), never
// producing NaN. Per row, not against the largest diagonal entry: a positive definite pivot may
// span many decades (a long revolute chain's articulated inertia about its free axis vs its
// constrained axes; a light body carrying a heavy subtree) without being singular.
constexpr double cRelativePivot = 1e-12;

template <int N> inline bool choleskyInPlace(double* a)
{
    double scale = 0.0;
    for (int i = 0; i < N; ++i)
    {
        scale = std::max(scale, std::abs(a[i * (N + 1)]));
    }
    if (!(scale > 0.0) || !std::isfinite(scale))
    {
        return false;
    }
    for (int j = 0; j < N; ++j)
    {
        const double diagonal = a[j + j * N];
        double d = diagonal;
        for (int k = 0; k < j; ++k)
        {
            d -= a[j + k * N] * a[j + k * N];
        }
        if (!(d > cRelativePivot * diagonal))
        {
            return false;
        }
        const double inverse = 1.0 / std::sqrt(d);
        a[j + j * N] = inverse;
        for (int i = j + 1; i < N; ++i)
        {
            double s = a[i + j * N];
            for (int k = 0; k < j; ++k)
            {
                s -= a[i + k * N] * a[j + k * N];
            }
            a[i + j * N] = s * inverse;
        }
    }
    return true;
}

// x <- (L L^T)^-1 x for the N x N factor l of choleskyInPlace, on the C columns of the N x C
// column-major x.
template <int N, int C> inline void choleskySolveInPlace(const double* l, double* x)
{
    for (int i = 0; i < N; ++i)
    {
        for (int c = 0; c < C; ++c)
        {
            double s = x[i + c * N];
            for (int k = 0; k < i; ++k)
            {
                s -= l[i + k * N] * x[k + c * N];
            }
            x[i + c * N] = s * l[i + i * N];
        }
    }
    for (int i = N - 1; i >= 0; --i)
    {
        for (int c = 0; c < C; ++c)
        {
            double s = x[i + c * N];
            for (int k = i + 1; k < N; ++k)
            {
                s -= l[k + i * N] * x[k + c * N];
            }
            x[i + c * N] = s * l[i + i * N];
        }
    }
}

// The same for any n (delassus): on the top n rows of z.
void choleskySolveInPlace(const double* l, int n, Mat6& z)
{
    for (int c = 0; c < 6; ++c)
    {
        for (int i = 0; i < n; ++i)
        {
            double s = z(i, c);
            for (int k = 0; k < i; ++k)
            {
                s -= l[i + k * n] * z(k, c);
            }
            z(i, c) = s * l[i + i * n];
        }
        for (int i = n - 1; i >= 0; --i)
        {
            double s = z(i, c);
            for (int k = i + 1; k < n; ++k)
            {
                s -= l[k + i * n] * z(k, c);
            }
            z(i, c) = s * l[i + i * n];
        }
    }
}

// Calls f(std::integral_constant<int, rows>) for rows = 1..6.
template <typename F> inline void withRows(int rows, F&& f)
{
    switch (rows)
    {
    case 1:
        f(std::integral_constant<int, 1>{});
        return;
    case 2:
        f(std::integral_constant<int, 2>{});
        return;
    case 3:
        f(std::integral_constant<int, 3>{});
        return;
    case 4:
        f(std::integral_constant<int, 4>{});
        return;
    case 5:
        f(std::integral_constant<int, 5>{});
        return;
    case 6:
        f(std::integral_constant<int, 6>{});
        return;
    default:
        throw std::logic_error("tree solver: a joint block must have 1 to 6 rows");
    }
}

inline void prefetch(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}

inline void prefetchForWrite(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1);
#else
    (void)p;
#endif
}

// Every cache line of [p, p + bytes).
inline void prefetchRange(const void* p, std::size_t bytes)
{
    const char* c = static_cast<const char*>(p);
    for (std::size_t offset = 0; offset < bytes; offset += 64)
    {
        prefetch(c + offset);
    }
    prefetch(c + bytes - 1);
}

// A node's pivot before any child edge is eliminated: its mass matrix (lower triangle).
inline void setMassMatrix(double* pivot, double mass, const Mat3& inertia)
{
    for (int j = 0; j < 6; ++j)
    {
        for (int i = j; i < 6; ++i)
        {
            pivot[i + j * 6] = 0.0;
        }
    }
    for (int i = 0; i < 3; ++i)
    {
        pivot[i * 7] = mass;
        for (int k = i; k < 3; ++k)
        {
            pivot[(3 + k) + (3 + i) * 6] = inertia(k, i);
        }
    }
}

// §3 step 2 for node b (6 rows) whose edge e has R rows (R = 0: no edge, a free root). `block`
// holds D_b on entry; on exit its Cholesky factor, then L_b = D_b^-1 J^T (6 x R). The edge's
// pivot gets its only contribution: -D_e = J D_b^-1 J^T (R x R at edgePivot). J: 6 x 6
// column-major, rows 0..R-1 used.
template <int R> inline bool factorNode(double* block, const double* J, double* edgePivot)
{
    if (!choleskyInPlace<6>(block))
    {
        return false;
    }
    if constexpr (R > 0)
    {
        double* l = block + 36;
        for (int c = 0; c < R; ++c)
        {
            for (int i = 0; i < 6; ++i)
            {
                l[i + c * 6] = J[c + i * 6];
            }
        }
        choleskySolveInPlace<6, R>(block, l);
        for (int j = 0; j < R; ++j)
        {
            for (int i = j; i < R; ++i)
            {
                double s = 0.0;
                for (int k = 0; k < 6; ++k)
                {
                    s += J[i + k * 6] * l[k + j * 6];
                }
                edgePivot[i + j * R] = s;
            }
        }
    }
    return true;
}

// §3 step 2 for edge e (R rows) with (HasParent) or without a parent node. `block` holds -D_e on
// entry; on exit its Cholesky factor, then L_e = D_e^-1 J (R x 6). The parent node's pivot
// (6 x 6 at parentPivot) loses J^T D_e^-1 J; it starts from its mass matrix when e is its first
// child.
template <int R, bool HasParent>
inline bool factorEdge(double* block, const double* J, double* parentPivot, bool firstChild, double mass,
                       const Mat3* inertia)
{
    if (!choleskyInPlace<R>(block))
    {
        return false;
    }
    if constexpr (HasParent)
    {
        double* l = block + R * R;
        for (int c = 0; c < 6; ++c)
        {
            for (int i = 0; i < R; ++i)
            {
                l[i + c * R] = -J[i + c * 6];
            }
        }
        choleskySolveInPlace<R, 6>(block, l); // L_e = D_e^-1 J = -(-D_e)^-1 J
        if (firstChild)
        {
            setMassMatrix(parentPivot, mass, *inertia);
        }
        for (int j = 0; j < 6; ++j)
        {
            for (int i = j; i < 6; ++i)
            {
                double s = 0.0;
                for (int k = 0; k < R; ++k)
                {
                    s += J[k + i * 6] * l[k + j * R];
                }
                parentPivot[i + j * 6] -= s;
            }
        }
    }
    return true;
}

// §3 step 3, forward sweep at block b (N rows, parent P rows, P = 0 without a parent): z_b is
// final, so z_p -= L_b^T z_b, then z_b <- D_b^-1 z_b (Negated: the factor is of -D_b).
template <int N, int P, bool Negated> inline void forwardBlock(const double* block, double* zb, double* zp)
{
    if constexpr (P > 0)
    {
        const double* l = block + N * N;
        for (int j = 0; j < P; ++j)
        {
            double s = 0.0;
            for (int k = 0; k < N; ++k)
            {
                s += l[k + j * N] * zb[k];
            }
            zp[j] -= s;
        }
    }
    choleskySolveInPlace<N, 1>(block, zb);
    if constexpr (Negated)
    {
        for (int i = 0; i < N; ++i)
        {
            zb[i] = -zb[i];
        }
    }
}

// Backward sweep at block b: x_b -= L_b x_p.
template <int N, int P> inline void backwardBlock(const double* block, double* xb, const double* xp)
{
    const double* l = block + N * N;
    for (int i = 0; i < N; ++i)
    {
        double s = 0.0;
        for (int k = 0; k < P; ++k)
        {
            s += l[i + k * N] * xp[k];
        }
        xb[i] -= s;
    }
}

// How many blocks ahead the sweeps prefetch (twice that for the parent's block table entry).
constexpr std::size_t cAhead = 8;

} // namespace

void TreeSolver::applyPivotInverse(int block, Mat6& z) const
{
    const BlockInfo& info = mBlocks[static_cast<std::size_t>(block)];
    choleskySolveInPlace(mArena.data() + info.offset, info.dim, z);
    if (info.flags & cEdge)
    {
        z.topRows(info.dim) = -z.topRows(info.dim);
    }
}

void TreeSolver::delassus(const std::vector<ExtraBlock>& blocks, int rows, Eigen::MatrixXd& G)
{
    const FrontierLayout& layout = *mSystem->layout;
    mSlotOfBody.assign(mSystem->model->bodies.size(), -1);
    std::vector<int> bodies;
    for (const ExtraBlock& block : blocks)
    {
        for (int body : {block.bodyA, block.bodyB})
        {
            if (body >= 0 && mSlotOfBody[static_cast<std::size_t>(body)] < 0)
            {
                mSlotOfBody[static_cast<std::size_t>(body)] = static_cast<int>(bodies.size());
                bodies.push_back(body);
            }
        }
    }
    // Forward sweeps from each body's node to its root (block indices increase along a path).
    mPaths.resize(bodies.size());
    for (std::size_t s = 0; s < bodies.size(); ++s)
    {
        std::vector<PathEntry>& path = mPaths[s];
        path.clear();
        int block = layout.bodyBlock[static_cast<std::size_t>(bodies[s])];
        Mat6 z = Mat6::Identity();
        while (block >= 0)
        {
            PathEntry entry;
            entry.block = block;
            entry.Z = z;
            entry.W = z;
            applyPivotInverse(block, entry.W);
            path.push_back(entry);
            const BlockInfo& info = mBlocks[static_cast<std::size_t>(block)];
            if (info.parent < 0)
            {
                break;
            }
            const int pd = info.parentDim;
            const Eigen::Map<const Eigen::MatrixXd> coupling(mArena.data() + info.offset + info.dim * info.dim,
                                                             info.dim, pd);
            Mat6 next = Mat6::Zero();
            next.topRows(pd).noalias() = -coupling.transpose() * z.topRows(info.dim);
            z = next;
            block = info.parent;
        }
    }
    // K_ij over the common suffix of the two paths.
    const std::size_t k = bodies.size();
    std::vector<Mat6> K(k * k, Mat6::Zero());
    for (std::size_t i = 0; i < k; ++i)
    {
        for (std::size_t j = i; j < k; ++j)
        {
            const std::vector<PathEntry>& a = mPaths[i];
            const std::vector<PathEntry>& b = mPaths[j];
            std::size_t ia = 0, ib = 0;
            while (ia < a.size() && ib < b.size() && a[ia].block != b[ib].block)
            {
                if (a[ia].block < b[ib].block)
                {
                    ++ia;
                }
                else
                {
                    ++ib;
                }
            }
            Mat6 sum = Mat6::Zero();
            for (; ia < a.size() && ib < b.size(); ++ia, ++ib)
            {
                const int dim = mBlocks[static_cast<std::size_t>(a[ia].block)].dim;
                sum.noalias() += a[ia].Z.topRows(dim).transpose() * b[ib].W.topRows(dim);
            }
            K[i * k + j] = sum;
            K[j * k + i] = sum.transpose();
        }
    }
    // G_rs = sum over the blocks' bodies of J_r,x K_xy J_s,y^T.
    G.setZero(rows, rows);
    for (const ExtraBlock& bi : blocks)
    {
        for (const ExtraBlock& bj : blocks)
        {
            if (bj.offset < bi.offset)
            {
                continue;
            }
            auto g = G.block(bi.offset, bj.offset, bi.count, bj.count);
            for (int sideI = 0; sideI < 2; ++sideI)
            {
                const int x = sideI == 0 ? bi.bodyA : bi.bodyB;
                if (x < 0)
                {
                    continue;
                }
                const Mat6& Ji = sideI == 0 ? bi.J_A : bi.J_B;
                for (int sideJ = 0; sideJ < 2; ++sideJ)
                {
                    const int y = sideJ == 0 ? bj.bodyA : bj.bodyB;
                    if (y < 0)
                    {
                        continue;
                    }
                    const Mat6& Jj = sideJ == 0 ? bj.J_A : bj.J_B;
                    const std::size_t sx = static_cast<std::size_t>(mSlotOfBody[static_cast<std::size_t>(x)]);
                    const std::size_t sy = static_cast<std::size_t>(mSlotOfBody[static_cast<std::size_t>(y)]);
                    g.noalias() += Ji.topRows(bi.count) * K[sx * k + sy] * Jj.topRows(bj.count).transpose();
                }
            }
            if (bj.offset != bi.offset)
            {
                G.block(bj.offset, bi.offset, bj.count, bi.count) = g.transpose();
            }
        }
    }
}

void TreeSolver::factor(const RowSystem& system)
{
    mSystem = &system;
    const Model& model = *system.model;
    const FrontierLayout& layout = *system.layout;
    const std::size_t nblocks = layout.blocks.size();

    // Block table and arena offsets: one pass over the layout. A node's pivot starts as M_i, an
    // edge's as 0; rather than a pass that writes them, each pivot is set by its first child (or
    // by the block itself when it has none), so the arena is written once, in layout order.
    mBlocks.resize(nblocks);
    mSeen.assign(nblocks, 0);
    std::size_t offset = 0;
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        BlockInfo& info = mBlocks[b];
        const bool edge = block.kind == LayoutBlock::Kind::Edge;
        // An edge's parent is a node (6 rows, checked below); a node's parent is its edge.
        const int parentDim =
            block.parent < 0 ? 0 : edge ? 6 : layout.blocks[static_cast<std::size_t>(block.parent)].dim;
        if (block.dim < 1 || block.dim > 6 || (!edge && block.dim != 6) || parentDim < 0 || parentDim > 6)
        {
            throw std::logic_error("tree solver: malformed frontier layout");
        }
        info.offset = static_cast<std::uint32_t>(offset);
        info.parent = block.parent;
        info.index = block.index;
        info.dim = static_cast<std::uint8_t>(block.dim);
        info.parentDim = static_cast<std::uint8_t>(parentDim);
        info.flags = edge ? cEdge : 0;
        if (mSeen[b])
        {
            info.flags |= cHasChildren;
        }
        if (block.parent >= 0 && !mSeen[static_cast<std::size_t>(block.parent)])
        {
            mSeen[static_cast<std::size_t>(block.parent)] = 1;
            info.flags |= cFirstChild;
        }
        offset += static_cast<std::size_t>(block.dim) * static_cast<std::size_t>(block.dim + parentDim);
        if (offset > std::numeric_limits<std::uint32_t>::max())
        {
            throw std::length_error("tree solver: system too large");
        }
    }
    mArena.resize(offset);
    mZ.resize(nblocks);
    mUnmappedBodies.clear();
    for (std::size_t i = 0; i < layout.bodyBlock.size(); ++i)
    {
        if (layout.bodyBlock[i] < 0)
        {
            mUnmappedBodies.push_back(static_cast<int>(i));
        }
    }
    mUnmappedJoints.clear();
    for (std::size_t j = 0; j < layout.jointBlock.size(); ++j)
    {
        if (layout.jointBlock[j] < 0)
        {
            mUnmappedJoints.push_back(static_cast<int>(j));
        }
    }

    // §3 step 2: eliminate in layout order.
    double* arena = mArena.data();
    const BlockInfo* blocks = mBlocks.data();
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        if (b + 2 * cAhead < nblocks && blocks[b + 2 * cAhead].parent >= 0)
        {
            prefetch(&blocks[blocks[b + 2 * cAhead].parent]);
        }
        if (b + cAhead < nblocks)
        {
            const BlockInfo& ahead = blocks[b + cAhead];
            if (ahead.flags & cEdge)
            {
                if (ahead.parent >= 0)
                {
                    const BlockInfo& node = blocks[ahead.parent];
                    prefetchRange(arena + node.offset, 36 * sizeof(double));
                    if (ahead.flags & cFirstChild)
                    {
                        prefetch(&system.mass[static_cast<std::size_t>(node.index)]);
                        prefetchRange(&system.inertia_W[static_cast<std::size_t>(node.index)], sizeof(Mat3));
                    }
                }
            }
            else
            {
                if (!(ahead.flags & cHasChildren))
                {
                    prefetch(&system.mass[static_cast<std::size_t>(ahead.index)]);
                    prefetchRange(&system.inertia_W[static_cast<std::size_t>(ahead.index)], sizeof(Mat3));
                }
                if (ahead.parent >= 0)
                {
                    const std::size_t joint = static_cast<std::size_t>(blocks[ahead.parent].index);
                    prefetch(&model.joints[joint].child);
                    prefetchRange(&system.joints[joint], sizeof(JointRows));
                }
            }
        }

        const BlockInfo& info = blocks[b];
        double* own = arena + info.offset;
        const std::size_t index = static_cast<std::size_t>(info.index);
        bool ok = true;
        if (!(info.flags & cEdge))
        {
            if (!(info.flags & cHasChildren))
            {
                setMassMatrix(own, system.mass[index], system.inertia_W[index]);
            }
            if (info.parent < 0)
            {
                ok = factorNode<0>(own, nullptr, nullptr);
            }
            else
            {
                // Node i -> its edge e: H_ie = J_ei^T (6 x r); -D_e = J D_i^-1 J^T.
                const BlockInfo& edge = blocks[info.parent];
                const std::size_t joint = static_cast<std::size_t>(edge.index);
                const JointRows& rows = system.joints[joint];
                const double* J = (model.joints[joint].child == info.index ? rows.J_b : rows.J_a).data();
                withRows(info.parentDim,
                         [&](auto r) { ok = factorNode<decltype(r)::value>(own, J, arena + edge.offset); });
            }
            if (!ok)
            {
                const Body& body = model.bodies[index];
                std::ostringstream msg;
                msg << "body '" << body.name << "': mass matrix is not positive definite";
                throw SingularJointError(body.name, msg.str());
            }
            continue;
        }
        // Edge e -> its parent node n: H_en = J_en (r x 6); D_n -= J^T D_e^-1 J.
        const Joint& joint = model.joints[index];
        if (info.parent < 0)
        {
            withRows(info.dim, [&](auto r)
                     { ok = factorEdge<decltype(r)::value, false>(own, nullptr, nullptr, false, 0.0, nullptr); });
        }
        else
        {
            const BlockInfo& node = blocks[info.parent];
            if ((node.flags & cEdge) || node.dim != 6)
            {
                throw std::logic_error("tree solver: malformed frontier layout");
            }
            const std::size_t parentBody = static_cast<std::size_t>(node.index);
            const JointRows& rows = system.joints[index];
            const double* J = (joint.child == node.index ? rows.J_b : rows.J_a).data();
            const bool first = info.flags & cFirstChild;
            withRows(info.dim,
                     [&](auto r)
                     {
                         ok = factorEdge<decltype(r)::value, true>(
                             own, J, arena + node.offset, first, first ? system.mass[parentBody] : 0.0,
                             first ? &system.inertia_W[parentBody] : nullptr);
                     });
        }
        if (!ok)
        {
            std::ostringstream msg;
            msg << "joint '" << joint.name << "' (" << jointTypeName(joint.type)
                << "): its constraint rows are dependent or degenerate at this configuration";
            throw SingularJointError(joint.name, msg.str());
        }
    }
}

void TreeSolver::solve(const BlockVector& rhs, BlockVector& solution)
{
    const std::size_t nblocks = mBlocks.size();
    const BlockInfo* blocks = mBlocks.data();
    const double* arena = mArena.data();
    Vec6* z = mZ.data();
    // Forward, front to back. The KKT right-hand side (p for nodes, c for edges) enters a block's
    // z when the block is reached (a leaf) or when its first child is (every rhs read happens
    // here, before `solution` is written, so the two may be the same object).
    auto rhsOf = [&](const BlockInfo& info) -> const Vec6&
    {
        return (info.flags & cEdge) ? rhs.joint[static_cast<std::size_t>(info.index)]
                                    : rhs.body[static_cast<std::size_t>(info.index)];
    };
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        if (b + 2 * cAhead < nblocks && (blocks[b + 2 * cAhead].flags & cFirstChild))
        {
            prefetch(&blocks[blocks[b + 2 * cAhead].parent]);
        }
        if (b + cAhead < nblocks)
        {
            const BlockInfo& ahead = blocks[b + cAhead];
            if (!(ahead.flags & cHasChildren))
            {
                prefetchRange(&rhsOf(ahead), sizeof(Vec6));
            }
            if (ahead.parent >= 0)
            {
                prefetchRange(&z[ahead.parent], sizeof(Vec6));
                if (ahead.flags & cFirstChild)
                {
                    prefetchRange(&rhsOf(blocks[ahead.parent]), sizeof(Vec6));
                }
            }
        }

        const BlockInfo& info = blocks[b];
        const double* own = arena + info.offset;
        double* zb = z[b].data();
        if (!(info.flags & cHasChildren))
        {
            z[b] = rhsOf(info);
        }
        double* zp = nullptr;
        if (info.parent >= 0)
        {
            Vec6& parent = z[static_cast<std::size_t>(info.parent)];
            if (info.flags & cFirstChild)
            {
                parent = rhsOf(blocks[info.parent]);
            }
            zp = parent.data();
        }
        if (!(info.flags & cEdge))
        {
            if (zp == nullptr)
            {
                forwardBlock<6, 0, false>(own, zb, nullptr);
            }
            else
            {
                withRows(info.parentDim,
                         [&](auto r) { forwardBlock<6, decltype(r)::value, false>(own, zb, zp); });
            }
        }
        else if (zp == nullptr)
        {
            withRows(info.dim, [&](auto r) { forwardBlock<decltype(r)::value, 0, true>(own, zb, nullptr); });
        }
        else
        {
            withRows(info.dim, [&](auto r) { forwardBlock<decltype(r)::value, 6, true>(own, zb, zp); });
        }
    }
    // Backward (§3 step 3): x_b -= L_b x_p from the last block to the first, each x_b written
    // out as soon as it is final. The KKT unknown of an edge is -lambda.
    solution.resize(rhs.body.size(), rhs.joint.size());
    for (std::size_t b = nblocks; b-- > 0;)
    {
        if (b >= cAhead)
        {
            const BlockInfo& ahead = blocks[b - cAhead];
            if (ahead.parent >= 0)
            {
                prefetchRange(&z[ahead.parent], sizeof(Vec6));
            }
            prefetchForWrite((ahead.flags & cEdge) ? &solution.joint[static_cast<std::size_t>(ahead.index)]
                                                   : &solution.body[static_cast<std::size_t>(ahead.index)]);
        }
        const BlockInfo& info = blocks[b];
        const double* own = arena + info.offset;
        double* xb = z[b].data();
        const double* xp = info.parent >= 0 ? z[static_cast<std::size_t>(info.parent)].data() : nullptr;
        if (!(info.flags & cEdge))
        {
            if (xp != nullptr)
            {
                withRows(info.parentDim, [&](auto r) { backwardBlock<6, decltype(r)::value>(own, xb, xp); });
            }
            solution.body[static_cast<std::size_t>(info.index)] = z[b];
            continue;
        }
        withRows(info.dim,
                 [&](auto r)
                 {
                     constexpr int R = decltype(r)::value;
                     if (xp != nullptr)
                     {
                         backwardBlock<R, 6>(own, xb, xp);
                     }
                     Vec6 lambda = Vec6::Zero();
                     lambda.head<R>() = -z[b].head<R>();
                     solution.joint[static_cast<std::size_t>(info.index)] = lambda;
                 });
    }
    // Bodies and joints without a block (static bodies, loop joints) get zero.
    const FrontierLayout& layout = *mSystem->layout;
    for (int i : mUnmappedBodies)
    {
        solution.body[static_cast<std::size_t>(i)].setZero();
    }
    for (std::size_t i = layout.bodyBlock.size(); i < solution.body.size(); ++i)
    {
        solution.body[i].setZero();
    }
    for (int j : mUnmappedJoints)
    {
        solution.joint[static_cast<std::size_t>(j)].setZero();
    }
    for (std::size_t j = layout.jointBlock.size(); j < solution.joint.size(); ++j)
    {
        solution.joint[j].setZero();
    }
}

} // namespace frontier::core
