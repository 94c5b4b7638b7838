// core/tree_solver.cpp: O(n) factor and solve in frontier order (docs/method.md §3, eqs. (5)-(6)).
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

#include "core/fixed_rows.h"
#include "core/packed_cholesky.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace frontier::core
{

namespace
{

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

// A node's pivot: its mass matrix M_i (lower triangle), set (a leaf) or added to the terms of its
// eliminated child edges.
inline void setMassMatrix(double* pivot, double mass, const Mat3& inertia)
{
    FRONTIER_UNROLL
    for (int j = 0; j < 6; ++j)
    {
        FRONTIER_UNROLL
        for (int i = j; i < 6; ++i)
        {
            pivot[tri<6>(i, j)] = 0.0;
        }
    }
    FRONTIER_UNROLL
    for (int i = 0; i < 3; ++i)
    {
        pivot[tri<6>(i, i)] = mass;
        FRONTIER_UNROLL
        for (int k = i; k < 3; ++k)
        {
            pivot[tri<6>(3 + k, 3 + i)] = inertia(k, i);
        }
    }
}

// docs/method.md §7a: h^2 k on the rotational diagonal (kg m^2).
inline void addGeometricInertia(double* pivot, double added)
{
    for (int i = 3; i < 6; ++i)
    {
        pivot[tri<6>(i, i)] += added;
    }
}

inline void addMassMatrix(double* pivot, double mass, const Mat3& inertia)
{
    FRONTIER_UNROLL
    for (int i = 0; i < 3; ++i)
    {
        pivot[tri<6>(i, i)] += mass;
        FRONTIER_UNROLL
        for (int k = i; k < 3; ++k)
        {
            pivot[tri<6>(3 + k, 3 + i)] += inertia(k, i);
        }
    }
}

// §3 step 2 for node b (6 rows) whose edge e has R rows (R = 0: no edge, a free root). `block`
// holds D_b on entry; on exit its Cholesky factor, then L_b = D_b^-1 J^T (6 x R). The edge's
// pivot gets its only contribution: -D_e = J D_b^-1 J^T (R x R at edgePivot). J: R x 6
// row-major (JointRowsTable::Rows).
template <int R> inline bool factorNode(double* block, const double* J, double* edgePivot)
{
    if (!choleskyInPlace<6>(block))
    {
        return false;
    }
    if constexpr (R > 0)
    {
        double* l = block + cTri6;
        FRONTIER_UNROLL
        for (int c = 0; c < R; ++c)
        {
            FRONTIER_UNROLL
            for (int i = 0; i < 6; ++i)
            {
                l[i + c * 6] = J[c * 6 + i]; // J(c, i), row-major
            }
        }
        choleskySolveInPlace<6, R>(block, l);
        FRONTIER_UNROLL
        for (int j = 0; j < R; ++j)
        {
            FRONTIER_UNROLL
            for (int i = j; i < R; ++i)
            {
                double s = 0.0;
                FRONTIER_UNROLL
                for (int k = 0; k < 6; ++k)
                {
                    s += J[i * 6 + k] * l[k + j * 6];
                }
                edgePivot[tri<R>(i, j)] = s;
            }
        }
    }
    return true;
}

// §3 step 2 for edge e (R rows) with (HasParent) or without a parent node. `block` holds -D_e on
// entry; on exit its Cholesky factor, then L_e = D_e^-1 J (R x 6). The parent node's pivot
// (6 x 6 at parentPivot) loses J^T D_e^-1 J; its first child sets it, its mass matrix is added
// when the node itself is reached (factorNode's caller).
template <int R, bool HasParent>
inline bool factorEdge(double* block, const double* J, double* parentPivot, bool firstChild)
{
    if (!choleskyInPlace<R>(block))
    {
        return false;
    }
    if constexpr (HasParent)
    {
        double* l = block + triSize(R);
        FRONTIER_UNROLL
        for (int c = 0; c < 6; ++c)
        {
            FRONTIER_UNROLL
            for (int i = 0; i < R; ++i)
            {
                l[i + c * R] = -J[i * 6 + c];
            }
        }
        choleskySolveInPlace<R, 6>(block, l); // L_e = D_e^-1 J = -(-D_e)^-1 J
        FRONTIER_UNROLL
        for (int j = 0; j < 6; ++j)
        {
            FRONTIER_UNROLL
            for (int i = j; i < 6; ++i)
            {
                double s = 0.0;
                FRONTIER_UNROLL
                for (int k = 0; k < R; ++k)
                {
                    s += J[k * 6 + i] * l[k + j * R];
                }
                if (firstChild)
                {
                    parentPivot[tri<6>(i, j)] = -s;
                }
                else
                {
                    parentPivot[tri<6>(i, j)] -= s;
                }
            }
        }
    }
    return true;
}

// §3 step 3, forward sweep at block b (N rows, parent P rows, P = 0 without a parent): z_b is
// final, so z_p -= L_b^T z_b (the first child sets z_p = -L_b^T z_b; the parent adds its own
// right-hand side when it is reached), then z_b <- D_b^-1 z_b (Negated: the factor is of -D_b).
template <int N, int P, bool Negated>
inline void forwardBlock(const double* block, double* zb, double* zp, bool firstChild)
{
    if constexpr (P > 0)
    {
        const double* l = block + triSize(N);
        FRONTIER_UNROLL
        for (int j = 0; j < P; ++j)
        {
            double s = 0.0;
            FRONTIER_UNROLL
            for (int k = 0; k < N; ++k)
            {
                s += l[k + j * N] * zb[k];
            }
            zp[j] = firstChild ? -s : zp[j] - s;
        }
    }
    choleskySolveInPlace<N, 1>(block, zb);
    if constexpr (Negated)
    {
        FRONTIER_UNROLL
        for (int i = 0; i < N; ++i)
        {
            zb[i] = -zb[i];
        }
    }
}

// Backward sweep at block b: x_b -= L_b x_p.
template <int N, int P> inline void backwardBlock(const double* block, double* xb, const double* xp)
{
    const double* l = block + triSize(N);
    FRONTIER_UNROLL
    for (int i = 0; i < N; ++i)
    {
        double s = 0.0;
        FRONTIER_UNROLL
        for (int k = 0; k < P; ++k)
        {
            s += l[i + k * N] * xp[k];
        }
        xb[i] -= s;
    }
}

// How many blocks ahead the sweeps prefetch.
constexpr std::size_t cAhead = 8;

// A right-hand side may leave its body part empty for zero momenta (the drift correction's,
// core/step/drift_correction.h): body i's part, and the bodies of the solution.
const Vec6 cNoMomentum = Vec6::Zero();
inline const Vec6& bodyRhs(const BlockVector& rhs, std::size_t i)
{
    return rhs.body.empty() ? cNoMomentum : rhs.body[i];
}
inline std::size_t solutionBodies(const BlockVector& rhs, const RowSystem& system)
{
    return rhs.body.empty() ? system.model->bodies.size() : rhs.body.size();
}

} // namespace

void TreeSolver::factor(const RowSystem& system)
{
    eliminateAll(system, nullptr);
}

void TreeSolver::factorAndSolve(const RowSystem& system, const BlockVector& rhs, BlockVector& solution)
{
    eliminateAll(system, &rhs); // the forward sweep rides along with the elimination
    solution.resize(solutionBodies(rhs, system), rhs.joint.size());
    backwardSweep(solution);
}

// The block table and the arena offsets of `layout`: one pass over it. Pivots are not
// initialized in a pass of their own: a block's first child sets its pivot, and a node adds its
// mass matrix when it is reached, so the arena is written in layout order and only the parent's
// pivot is touched out of order. A layout made by buildFrontierLayout is laid out once.
void TreeSolver::layOutBlocks(const FrontierLayout& layout)
{
    const std::size_t nblocks = layout.blocks.size();
    if (layout.id != 0 && layout.id == mBlocksOfLayout && mBlocks.size() == nblocks)
    {
        return;
    }
    mBlocksOfLayout = 0;
    mBlocks.resize(nblocks);
    mOffsets.resize(nblocks);
    mSeen.assign(nblocks, 0);
    std::size_t offset = 0;
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        BlockInfo& info = mBlocks[b];
        const bool edge = block.kind == LayoutBlock::Kind::Edge;
        // An edge's parent is a node (6 rows, checked below); a node's parent is its edge.
        const int parentDim = block.parent < 0 ? 0
                              : edge           ? 6
                                               : layout.blocks[static_cast<std::size_t>(block.parent)].dim;
        if (block.dim < 1 || block.dim > 6 || (!edge && block.dim != 6) || parentDim < 0 || parentDim > 6 ||
            block.parent >= static_cast<int>(nblocks) ||
            (block.parent >= 0 && block.parent <= static_cast<int>(b)))
        {
            throw std::logic_error("tree solver: malformed frontier layout");
        }
        mOffsets[b] = static_cast<std::uint32_t>(offset);
        info.parent = block.parent;
        info.index = block.index;
        info.dim = static_cast<std::uint8_t>(block.dim);
        info.parentDim = static_cast<std::uint8_t>(parentDim);
        info.flags = edge ? cEdge : 0;
        if (edge && block.childIsJointChild)
        {
            info.flags |= cChildIsJointChild;
        }
        if (edge && block.driveRows > 0)
        {
            info.flags |= cDriven;
        }
        if (mSeen[b])
        {
            info.flags |= cHasChildren;
        }
        if (block.parent >= 0 && !mSeen[static_cast<std::size_t>(block.parent)])
        {
            mSeen[static_cast<std::size_t>(block.parent)] = 1;
            info.flags |= cFirstChild;
        }
        offset += static_cast<std::size_t>(triSize(block.dim) + block.dim * parentDim);
        if (offset > std::numeric_limits<std::uint32_t>::max())
        {
            throw std::length_error("tree solver: system too large");
        }
    }
    // Each parent's arena offset next to its child's entry: the elimination then reaches (and
    // prefetches) a far-away parent pivot without first loading its offset from a random place.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const int parent = mBlocks[b].parent;
        mBlocks[b].parentOffset = parent >= 0 ? mOffsets[static_cast<std::size_t>(parent)] : 0;
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
    mBlocksOfLayout = layout.id;
}

// §3 step 2 in layout order; with a right-hand side, §3 step 3's forward sweep at each block as
// soon as it is eliminated (its factors are still in cache).
void TreeSolver::eliminateAll(const RowSystem& system, const BlockVector* rhs)
{
    mSystem = &system;
    const FrontierLayout& layout = *system.layout;
    const std::size_t nblocks = layout.blocks.size();
    layOutBlocks(layout);

    // §3 step 2: eliminate in layout order.
    double* arena = mArena.data();
    BlockInfo* blocks = mBlocks.data();
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        if (b + cAhead < nblocks)
        {
            const BlockInfo& ahead = blocks[b + cAhead];
            if (ahead.flags & cEdge)
            {
                if (ahead.parent >= 0)
                {
                    prefetchRange(arena + ahead.parentOffset, cTri6 * sizeof(double));
                }
            }
            else
            {
                prefetch(&system.mass[static_cast<std::size_t>(ahead.index)]);
                prefetchRange(&system.inertia_W[static_cast<std::size_t>(ahead.index)], sizeof(Mat3));
                if (ahead.parent >= 0)
                {
                    // The rows of both sides (the node reads one, its edge the other): J_a and
                    // J_b one after the other (JointRowsTable::rows).
                    const BlockInfo& edge = blocks[ahead.parent];
                    const JointRowsTable::Rows rows =
                        system.joints.rows(static_cast<std::size_t>(edge.index));
                    prefetchRange(rows.J_a, static_cast<std::size_t>(rows.capacity) * 12 * sizeof(double));
                }
            }
            if (rhs != nullptr)
            {
                prefetchRange((ahead.flags & cEdge) ? &rhs->joint[static_cast<std::size_t>(ahead.index)]
                                                    : &bodyRhs(*rhs, static_cast<std::size_t>(ahead.index)),
                              sizeof(Vec6));
                if (ahead.parent >= 0)
                {
                    prefetchForWrite(&mZ[static_cast<std::size_t>(ahead.parent)]);
                }
            }
        }

        eliminate(b);
        if (rhs != nullptr)
        {
            forwardStep(b, *rhs);
        }
    }
}

// §3 step 2 at block b: its pivot's factor, L_b, and its contribution to its parent's pivot.
void TreeSolver::eliminate(std::size_t b)
{
    const RowSystem& system = *mSystem;
    const Model& model = *system.model;
    double* arena = mArena.data();
    BlockInfo* blocks = mBlocks.data();
    const std::uint32_t* offsets = mOffsets.data();
    BlockInfo& info = blocks[b];
    double* own = arena + offsets[b];
    const std::size_t index = static_cast<std::size_t>(info.index);
    bool ok = true;
    if (!(info.flags & cEdge))
    {
        if (info.flags & cHasChildren)
        {
            addMassMatrix(own, system.mass[index], system.inertia_W[index]);
        }
        else
        {
            setMassMatrix(own, system.mass[index], system.inertia_W[index]);
        }
        if (!system.geometricInertia.empty())
        {
            addGeometricInertia(own, system.geometricInertia[index]);
        }
        if (info.parent < 0)
        {
            ok = factorNode<0>(own, nullptr, nullptr);
        }
        else
        {
            // Node i -> its edge e: H_ie = J_ei^T (6 x r); -D_e = J D_i^-1 J^T.
            const BlockInfo& edge = blocks[info.parent];
            const JointRowsTable::Rows rows = system.joints.rows(static_cast<std::size_t>(edge.index));
            const bool jointChild = edge.flags & cChildIsJointChild;
            const double* J = jointChild ? rows.J_b : rows.J_a;
            double* edgePivot = arena + info.parentOffset;
            withRows(info.parentDim, [&](auto r) { ok = factorNode<decltype(r)::value>(own, J, edgePivot); });
        }
        if (!ok)
        {
            const Body& body = model.bodies[index];
            std::ostringstream msg;
            msg << "body '" << body.name << "': mass matrix is not positive definite";
            throw SingularJointError(body.name, msg.str());
        }
        return;
    }
    if (info.flags & cDriven)
    {
        // Drive rows (core/joints/drive.h): J u + E lambda = c puts -E on the KKT diagonal, so the
        // pivot -D_e = J D_child^-1 J^T that the child node left gains +E.
        const JointRowsTable::Rows rows = system.joints.rows(index);
        for (int r = rows.constraintRows; r < rows.count; ++r)
        {
            own[tri(info.dim, r, r)] += rows.compliance[r - rows.firstDrive];
        }
    }
    // Edge e -> its parent node n: H_en = J_en (r x 6); D_n -= J^T D_e^-1 J. The node's side of
    // the joint is the one its child node is not on.
    if (info.parent < 0)
    {
        withRows(info.dim,
                 [&](auto r) { ok = factorEdge<decltype(r)::value, false>(own, nullptr, nullptr, false); });
    }
    else
    {
        if (info.parentDim != 6 || !(info.flags & cHasChildren))
        {
            throw std::logic_error("tree solver: malformed frontier layout");
        }
        const JointRowsTable::Rows rows = system.joints.rows(index);
        const double* J = (info.flags & cChildIsJointChild) ? rows.J_a : rows.J_b;
        double* parentPivot = arena + info.parentOffset;
        const bool first = info.flags & cFirstChild;
        withRows(info.dim,
                 [&](auto r) { ok = factorEdge<decltype(r)::value, true>(own, J, parentPivot, first); });
    }
    if (!ok)
    {
        const Joint& joint = model.joints[index];
        std::ostringstream msg;
        msg << "joint '" << joint.name << "' (" << jointTypeName(joint.type)
            << "): its constraint rows are dependent or degenerate at this configuration";
        throw SingularJointError(joint.name, msg.str());
    }
}

void TreeSolver::solve(const BlockVector& rhs, BlockVector& solution)
{
    const std::size_t nblocks = mBlocks.size();
    const BlockInfo* blocks = mBlocks.data();
    // Forward, front to back. Every rhs read happens here, before `solution` is written, so the
    // two may be the same object.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        if (b + cAhead < nblocks)
        {
            const BlockInfo& ahead = blocks[b + cAhead];
            prefetchRange((ahead.flags & cEdge) ? &rhs.joint[static_cast<std::size_t>(ahead.index)]
                                                : &bodyRhs(rhs, static_cast<std::size_t>(ahead.index)),
                          sizeof(Vec6));
            if (ahead.parent >= 0)
            {
                prefetchForWrite(&mZ[static_cast<std::size_t>(ahead.parent)]);
                prefetchForWrite(mZ[static_cast<std::size_t>(ahead.parent)].data() + 5);
            }
        }
        forwardStep(b, rhs);
    }
    solution.resize(solutionBodies(rhs, *mSystem), rhs.joint.size());
    backwardSweep(solution);
}

// §3 step 3, forward sweep at block b: the KKT right-hand side (p for nodes, c for edges) is
// added to z_b (its children's terms are in: they come earlier), then z_p -= L_b^T z_b and
// z_b <- D_b^-1 z_b.
void TreeSolver::forwardStep(std::size_t b, const BlockVector& rhs)
{
    const BlockInfo& info = mBlocks[b];
    const double* own = mArena.data() + mOffsets[b];
    Vec6* z = mZ.data();
    double* zb = z[b].data();
    const Vec6& rb = (info.flags & cEdge) ? rhs.joint[static_cast<std::size_t>(info.index)]
                                          : bodyRhs(rhs, static_cast<std::size_t>(info.index));
    if (info.flags & cHasChildren)
    {
        z[b] += rb;
    }
    else
    {
        z[b] = rb;
    }
    double* zp = info.parent >= 0 ? z[static_cast<std::size_t>(info.parent)].data() : nullptr;
    const bool first = info.flags & cFirstChild;
    if (!(info.flags & cEdge))
    {
        if (zp == nullptr)
        {
            forwardBlock<6, 0, false>(own, zb, nullptr, false);
        }
        else
        {
            withRows(info.parentDim,
                     [&](auto r) { forwardBlock<6, decltype(r)::value, false>(own, zb, zp, first); });
        }
    }
    else if (zp == nullptr)
    {
        withRows(info.dim,
                 [&](auto r) { forwardBlock<decltype(r)::value, 0, true>(own, zb, nullptr, false); });
    }
    else
    {
        withRows(info.dim, [&](auto r) { forwardBlock<decltype(r)::value, 6, true>(own, zb, zp, first); });
    }
}

// Backward (§3 step 3): x_b -= L_b x_p from the last block to the first, each x_b written out as
// soon as it is final (`solution` sized by the caller). The KKT unknown of an edge is -lambda.
void TreeSolver::backwardSweep(BlockVector& solution)
{
    const std::size_t nblocks = mBlocks.size();
    const BlockInfo* blocks = mBlocks.data();
    const std::uint32_t* offsets = mOffsets.data();
    const double* arena = mArena.data();
    Vec6* z = mZ.data();
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
        const double* own = arena + offsets[b];
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
