// core/tree_solver.cpp: O(n) factor and solve in frontier order (PAPER.md §3 steps 2 and 3).
#include "core/tree_solver.h"

#include <cmath>
#include <sstream>

namespace frontier::core
{

namespace
{

// In-place lower Cholesky of the top-left n x n of a. Returns false when a pivot falls below
// cRelativePivot times its own row's diagonal entry (cancellation: dependent rows), never
// producing NaN. Per row, not against the largest diagonal entry: a positive definite pivot may
// span many decades (a long revolute chain's articulated inertia about its free axis vs its
// constrained axes; a light body carrying a heavy subtree) without being singular.
constexpr double cRelativePivot = 1e-12;

bool choleskyInPlace(Mat6& a, int n)
{
    double scale = 0.0;
    for (int i = 0; i < n; ++i)
    {
        scale = std::max(scale, std::abs(a(i, i)));
    }
    if (!(scale > 0.0) || !std::isfinite(scale))
    {
        return false;
    }
    for (int j = 0; j < n; ++j)
    {
        const double diagonal = a(j, j);
        double d = diagonal;
        for (int k = 0; k < j; ++k)
        {
            d -= a(j, k) * a(j, k);
        }
        if (!(d > cRelativePivot * diagonal))
        {
            return false;
        }
        const double ljj = std::sqrt(d);
        a(j, j) = ljj;
        for (int i = j + 1; i < n; ++i)
        {
            double s = a(i, j);
            for (int k = 0; k < j; ++k)
            {
                s -= a(i, k) * a(j, k);
            }
            a(i, j) = s / ljj;
        }
    }
    return true;
}

// x <- (L L^T)^-1 x for the top-left n x n lower factor l, on `cols` columns of x.
template <typename Derived> void choleskySolveInPlace(const Mat6& l, int n, Eigen::MatrixBase<Derived>& x)
{
    for (int c = 0; c < x.cols(); ++c)
    {
        for (int i = 0; i < n; ++i)
        {
            double s = x(i, c);
            for (int k = 0; k < i; ++k)
            {
                s -= l(i, k) * x(k, c);
            }
            x(i, c) = s / l(i, i);
        }
        for (int i = n - 1; i >= 0; --i)
        {
            double s = x(i, c);
            for (int k = i + 1; k < n; ++k)
            {
                s -= l(k, i) * x(k, c);
            }
            x(i, c) = s / l(i, i);
        }
    }
}

} // namespace

void TreeSolver::applyPivotInverse(int block, Vec6& z) const
{
    const Factor& f = mFactors[static_cast<std::size_t>(block)];
    auto head = z.head(f.dim);
    choleskySolveInPlace(f.chol, f.dim, head);
    if (f.negated)
    {
        head = -head;
    }
}

void TreeSolver::applyPivotInverse(int block, Mat6& z) const
{
    const Factor& f = mFactors[static_cast<std::size_t>(block)];
    auto head = z.topRows(f.dim);
    choleskySolveInPlace(f.chol, f.dim, head);
    if (f.negated)
    {
        head = -head;
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
            const Factor& f = mFactors[static_cast<std::size_t>(block)];
            if (f.parent < 0)
            {
                break;
            }
            const int pd = mFactors[static_cast<std::size_t>(f.parent)].dim;
            Mat6 next = Mat6::Zero();
            next.topRows(pd).noalias() = -f.coupling.topLeftCorner(f.dim, pd).transpose() * z.topRows(f.dim);
            z = next;
            block = f.parent;
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
                const int dim = mFactors[static_cast<std::size_t>(a[ia].block)].dim;
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
    mFactors.resize(nblocks);
    mZ.resize(nblocks);

    // Pivots start as the diagonal blocks H_bb: M_i for nodes, 0 for edges.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        Factor& f = mFactors[b];
        f.dim = block.dim;
        f.parent = block.parent;
        f.negated = block.kind == LayoutBlock::Kind::Edge;
        f.chol.setZero();
        if (block.kind == LayoutBlock::Kind::Node)
        {
            const std::size_t i = static_cast<std::size_t>(block.index);
            f.chol.topLeftCorner<3, 3>() = system.mass[i] * Mat3::Identity();
            f.chol.bottomRightCorner<3, 3>() = system.inertia_W[i];
        }
    }

    // §3 step 2: eliminate in layout order. f.chol holds D_b (edges: -D_b) until factored.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        Factor& f = mFactors[b];
        if (!choleskyInPlace(f.chol, f.dim))
        {
            std::ostringstream msg;
            if (block.kind == LayoutBlock::Kind::Edge)
            {
                const Joint& joint = model.joints[static_cast<std::size_t>(block.index)];
                msg << "joint '" << joint.name << "' (" << jointTypeName(joint.type)
                    << "): its constraint rows are dependent or degenerate at this configuration";
                throw SingularJointError(joint.name, msg.str());
            }
            const Body& body = model.bodies[static_cast<std::size_t>(block.index)];
            msg << "body '" << body.name << "': mass matrix is not positive definite";
            throw SingularJointError(body.name, msg.str());
        }
        if (f.parent < 0)
        {
            continue;
        }
        Factor& pf = mFactors[static_cast<std::size_t>(f.parent)];
        const int pd = pf.dim;
        // H_bp: the coupling between this block and its parent block.
        if (block.kind == LayoutBlock::Kind::Node)
        {
            // Node i -> its edge e: H_ie = J_ei^T (6 x r); D_e -= J D_i^-1 J^T, i.e. -D_e += ...
            const LayoutBlock& edge = layout.blocks[static_cast<std::size_t>(f.parent)];
            const Joint& joint = model.joints[static_cast<std::size_t>(edge.index)];
            const JointRows& rows = system.joints[static_cast<std::size_t>(edge.index)];
            const Mat6& J = joint.child == block.index ? rows.J_b : rows.J_a;
            f.coupling.topLeftCorner(6, pd) = J.topRows(pd).transpose();
            auto lb = f.coupling.topLeftCorner(6, pd);
            choleskySolveInPlace(f.chol, 6, lb);
            pf.chol.topLeftCorner(pd, pd).noalias() += J.topRows(pd) * f.coupling.topLeftCorner(6, pd);
        }
        else
        {
            // Edge e -> its parent node n: H_en = J_en (r x 6); D_n -= J^T D_e^-1 J.
            const Joint& joint = model.joints[static_cast<std::size_t>(block.index)];
            const JointRows& rows = system.joints[static_cast<std::size_t>(block.index)];
            const int parentBody = layout.blocks[static_cast<std::size_t>(f.parent)].index;
            const Mat6& J = joint.child == parentBody ? rows.J_b : rows.J_a;
            f.coupling.topLeftCorner(f.dim, 6) = -J.topRows(f.dim);
            auto le = f.coupling.topLeftCorner(f.dim, 6);
            choleskySolveInPlace(f.chol, f.dim, le); // L_e = D_e^-1 J = -(-D_e)^-1 J
            pf.chol.noalias() -= J.topRows(f.dim).transpose() * f.coupling.topLeftCorner(f.dim, 6);
        }
    }
}

void TreeSolver::solve(const BlockVector& rhs, BlockVector& solution)
{
    const FrontierLayout& layout = *mSystem->layout;
    const std::size_t nblocks = layout.blocks.size();
    // KKT right-hand side: p for nodes, c for edges.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        mZ[b] = block.kind == LayoutBlock::Kind::Node ? rhs.body[static_cast<std::size_t>(block.index)]
                                                      : rhs.joint[static_cast<std::size_t>(block.index)];
    }
    // Forward: z_p -= L_b^T z_b.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const Factor& f = mFactors[b];
        if (f.parent >= 0)
        {
            const int pd = mFactors[static_cast<std::size_t>(f.parent)].dim;
            mZ[static_cast<std::size_t>(f.parent)].head(pd).noalias() -=
                f.coupling.topLeftCorner(f.dim, pd).transpose() * mZ[b].head(f.dim);
        }
    }
    // Diagonal: x_b = D_b^-1 z_b.
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        applyPivotInverse(static_cast<int>(b), mZ[b]);
    }
    // Backward (§3 step 3): x_b -= L_b x_p, from the last block to the first.
    for (std::size_t b = nblocks; b-- > 0;)
    {
        const Factor& f = mFactors[b];
        if (f.parent >= 0)
        {
            const int pd = mFactors[static_cast<std::size_t>(f.parent)].dim;
            mZ[b].head(f.dim).noalias() -=
                f.coupling.topLeftCorner(f.dim, pd) * mZ[static_cast<std::size_t>(f.parent)].head(pd);
        }
    }
    solution.resize(rhs.body.size(), rhs.joint.size());
    solution.setZero();
    for (std::size_t b = 0; b < nblocks; ++b)
    {
        const LayoutBlock& block = layout.blocks[b];
        if (block.kind == LayoutBlock::Kind::Node)
        {
            solution.body[static_cast<std::size_t>(block.index)] = mZ[b];
        }
        else
        {
            // The KKT unknown is -lambda.
            solution.joint[static_cast<std::size_t>(block.index)].head(block.dim) = -mZ[b].head(block.dim);
        }
    }
}

} // namespace frontier::core
