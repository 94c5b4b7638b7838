// core/tree_delassus.cpp: the Delassus matrix G = J_x H^-1 J_x^T of the extra rows (docs/method.md §5)
// from the tree factorization H = L D L^T of core/tree_solver.cpp, without one O(n) solve per row.
//
// With z_x = L^-1 e_x (the forward sweep of a unit impulse on body x: nonzero only on x's path
// to its root), (H^-1)_xy = sum over the blocks b common to both paths of z_x,b^T D_b^-1 z_y,b.
// The paths of x and y meet at a block c and coincide above it, where z_x,b = Phi(b <- c) z_x,c.
// So (H^-1)_xy = z_x,c^T X_c z_y,c with X_c = sum over b above c of Phi^T D_b^-1 Phi, the diagonal
// block of H^-1 at c. Those blocks follow top-down from the root (Takahashi's selected
// inversion): X_root = D_root^-1, X_c = D_c^-1 + L_c X_p(c) L_c^T. Carrying J_x^T instead of e_x,
// G_xy = A_x,c^T X_c A_y,c with A_x = L^-1 J_x^T: one small product per pair of bodies instead of
// a sum along their common path.
#include "core/delassus.h"
#include "core/fixed_rows.h"
#include "core/packed_cholesky.h"
#include "core/tree_solver.h"

#include <algorithm>

namespace frontier::core
{

namespace
{

// next = -L^T a: L is D x P (column-major), a is D x m, next P x m (the forward sweep's
// z_p -= L_b^T z_b for m columns at once).
template <int D, int P> void propagate(const double* l, const double* a, double* next, int m)
{
    const Eigen::Map<const Eigen::Matrix<double, D, P>> L(l);
    const Eigen::Map<const Eigen::Matrix<double, D, Eigen::Dynamic>> A(a, D, m);
    Eigen::Map<Eigen::Matrix<double, P, Eigen::Dynamic>> N(next, P, m);
    N.noalias() = -(L.transpose() * A);
}

// X(0:N, 0:N) = D_b^-1 from the block's packed Cholesky factor l (of -D_b for an edge).
template <int N> void pivotInverse(const double* l, bool negated, Mat6& X)
{
    Eigen::Matrix<double, N, N> inverse;
    choleskyInverse<N>(l, inverse.data());
    if (negated)
    {
        inverse = -inverse;
    }
    X.topLeftCorner<N, N>() = inverse;
}

// X(0:D, 0:D) += L Xp L^T with L D x P (column-major) and Xp the top-left P x P of `parent`.
template <int D, int P> void addCongruence(const double* l, const Mat6& parent, Mat6& X)
{
    const Eigen::Map<const Eigen::Matrix<double, D, P>> L(l);
    const Eigen::Matrix<double, D, P> LX = L * parent.topLeftCorner<P, P>();
    X.topLeftCorner<D, D>().noalias() += LX * L.transpose();
}

} // namespace

// Calls f(body, block, local offset) for each side of the part's blocks whose body is on the
// part's tree, in the part's order (a block with both bodies on the tree: A, then B).
template <typename F>
void TreeSolver::forEachSide(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part,
                             F&& f) const
{
    const std::vector<int>& treeOfBody = mSystem->layout->treeOfBody;
    for (std::size_t k = 0; k < part.blocks.size(); ++k)
    {
        const ExtraBlock& block = blocks[static_cast<std::size_t>(part.blocks[k])];
        for (int body : {block.bodyA, block.bodyB})
        {
            if (body >= 0 && (part.tree < 0 || treeOfBody[static_cast<std::size_t>(body)] == part.tree))
            {
                f(body, block, part.offsets[k]);
            }
        }
    }
}

void TreeSolver::delassusParts(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G,
                               std::span<const int> parts)
{
    const std::size_t nblocks = mBlocks.size();
    if (mSlotOfBody.size() != mSystem->model->bodies.size())
    {
        mSlotOfBody.assign(mSystem->model->bodies.size(), -1);
    }
    if (mDiagonalOf.size() != nblocks)
    {
        mDiagonalOf.assign(nblocks, -1);
    }
    for (int p : parts)
    {
        DelassusMatrix::Part& part = G.part(p);
        gatherSlots(blocks, part);
        layOutPaths();
        placeJacobians(blocks, part);
        sweepPathsForward();
        invertOnPaths();
        assembleDelassus(part.G);
        clearSlotMaps();
        setFreeDelassus(*mSystem, blocks, part);
    }
    G.touch();
}

// The part's bodies on its tree with extra rows (slots), and the part's rows each one carries, in
// stacking order.
void TreeSolver::gatherSlots(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part)
{
    mSlotBodies.clear();
    forEachSide(blocks, part,
                [&](int body, const ExtraBlock&, int)
                {
                    if (mSlotOfBody[static_cast<std::size_t>(body)] < 0)
                    {
                        mSlotOfBody[static_cast<std::size_t>(body)] = static_cast<int>(mSlotBodies.size());
                        mSlotBodies.push_back(body);
                    }
                });
    const std::size_t k = mSlotBodies.size();
    mSlotRows.resize(std::max(mSlotRows.size(), k));
    mPaths.resize(std::max(mPaths.size(), k));
    for (std::size_t s = 0; s < k; ++s)
    {
        mSlotRows[s].clear();
        mPaths[s].clear();
    }
    forEachSide(blocks, part,
                [&](int body, const ExtraBlock& block, int localOffset)
                {
                    std::vector<int>& slotRows =
                        mSlotRows[static_cast<std::size_t>(mSlotOfBody[static_cast<std::size_t>(body)])];
                    for (int r = 0; r < block.count; ++r)
                    {
                        slotRows.push_back(localOffset + r);
                    }
                });
}

// Each slot's path from its node to its root, and room for its A blocks (at most 6 x m_x each).
void TreeSolver::layOutPaths()
{
    const FrontierLayout& layout = *mSystem->layout;
    const std::size_t k = mSlotBodies.size();
    std::size_t poolSize = 0;
    for (std::size_t s = 0; s < k; ++s)
    {
        const std::size_t m = mSlotRows[s].size();
        for (int b = layout.bodyBlock[static_cast<std::size_t>(mSlotBodies[s])]; b >= 0;
             b = mBlocks[static_cast<std::size_t>(b)].parent)
        {
            mPaths[s].push_back({b, static_cast<std::uint32_t>(poolSize)});
            poolSize += 6 * m;
        }
    }
    mPool.resize(poolSize);
}

// Each body's J_x^T at its node, its columns in the order of its rows (one pass over the part's
// blocks, with a column cursor per slot).
void TreeSolver::placeJacobians(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part)
{
    const std::size_t k = mSlotBodies.size();
    mSlotColumn.assign(k, 0);
    forEachSide(blocks, part,
                [&](int body, const ExtraBlock& block, int)
                {
                    const std::size_t s =
                        static_cast<std::size_t>(mSlotOfBody[static_cast<std::size_t>(body)]);
                    const Mat6& J = body == block.bodyA ? block.J_A : block.J_B;
                    Eigen::Map<Eigen::Matrix<double, 6, Eigen::Dynamic>> columns(
                        mPool.data() + mPaths[s][0].offset + 6 * mSlotColumn[s], 6, block.count);
                    columns = J.topRows(block.count).transpose();
                    mSlotColumn[s] += block.count;
                });
}

// Forward sweeps, A_x = L^-1 J_x^T: from x's node, A_p = -L_b^T A_b up the path.
void TreeSolver::sweepPathsForward()
{
    const std::size_t k = mSlotBodies.size();
    for (std::size_t s = 0; s < k; ++s)
    {
        const int m = static_cast<int>(mSlotRows[s].size());
        const std::vector<PathEntry>& path = mPaths[s];
        for (std::size_t e = 0; e + 1 < path.size(); ++e)
        {
            const BlockInfo& info = mBlocks[static_cast<std::size_t>(path[e].block)];
            const double* coupling = mArena.data() + mOffsets[static_cast<std::size_t>(path[e].block)] +
                                     info.dim * (info.dim + 1) / 2; // L_b, dim x parentDim
            const double* a = mPool.data() + path[e].offset;
            double* next = mPool.data() + path[e + 1].offset;
            // A node's parent is its edge (r rows), an edge's parent a node (6 rows).
            const bool edge = info.flags & cEdge;
            withRows(edge ? info.dim : info.parentDim,
                     [&](auto r)
                     {
                         constexpr int R = decltype(r)::value;
                         if (edge)
                         {
                             propagate<R, 6>(coupling, a, next, m);
                         }
                         else
                         {
                             propagate<6, R>(coupling, a, next, m);
                         }
                     });
        }
    }
}

// X_c on the union of the paths, from the roots down (descending layout order).
void TreeSolver::invertOnPaths()
{
    const std::size_t k = mSlotBodies.size();
    mMarked.clear();
    for (std::size_t s = 0; s < k; ++s)
    {
        for (const PathEntry& entry : mPaths[s])
        {
            if (mDiagonalOf[static_cast<std::size_t>(entry.block)] >= 0)
            {
                break; // the rest of this path is marked already
            }
            mDiagonalOf[static_cast<std::size_t>(entry.block)] = 0;
            mMarked.push_back(entry.block);
        }
    }
    std::sort(mMarked.begin(), mMarked.end(), std::greater<>());
    mDiagonal.resize(std::max(mDiagonal.size(), mMarked.size()));
    for (std::size_t i = 0; i < mMarked.size(); ++i)
    {
        const int b = mMarked[i];
        mDiagonalOf[static_cast<std::size_t>(b)] = static_cast<int>(i);
        const BlockInfo& info = mBlocks[static_cast<std::size_t>(b)];
        Mat6& X = mDiagonal[i];
        const double* factor = mArena.data() + mOffsets[static_cast<std::size_t>(b)];
        withRows(info.dim, [&](auto r) { pivotInverse<decltype(r)::value>(factor, info.flags & cEdge, X); });
        if (info.parent >= 0)
        {
            const Mat6& parent =
                mDiagonal[static_cast<std::size_t>(mDiagonalOf[static_cast<std::size_t>(info.parent)])];
            const double* coupling =
                mArena.data() + mOffsets[static_cast<std::size_t>(b)] + info.dim * (info.dim + 1) / 2;
            const bool edge = info.flags & cEdge;
            withRows(edge ? info.dim : info.parentDim,
                     [&](auto r)
                     {
                         constexpr int R = decltype(r)::value;
                         if (edge)
                         {
                             addCongruence<R, 6>(coupling, parent, X);
                         }
                         else
                         {
                             addCongruence<6, R>(coupling, parent, X);
                         }
                     });
        }
    }
}

// G_xy = A_x,c^T X_c A_y,c for every pair of slots (all on the part's tree), c where their paths
// meet.
void TreeSolver::assembleDelassus(Eigen::MatrixXd& G)
{
    const std::size_t k = mSlotBodies.size();
    G.setZero();
    for (std::size_t x = 0; x < k; ++x)
    {
        const std::vector<PathEntry>& px = mPaths[x];
        const int mx = static_cast<int>(mSlotRows[x].size());
        for (std::size_t y = x; y < k; ++y)
        {
            const std::vector<PathEntry>& py = mPaths[y];
            std::size_t ix = 0, iy = 0;
            while (px[ix].block != py[iy].block) // block indices ascend along a path
            {
                if (px[ix].block < py[iy].block)
                {
                    ++ix;
                }
                else
                {
                    ++iy;
                }
            }
            const int c = px[ix].block;
            const int my = static_cast<int>(mSlotRows[y].size());
            const Mat6& X = mDiagonal[static_cast<std::size_t>(mDiagonalOf[static_cast<std::size_t>(c)])];
            // Two paths first meet at a node (an edge has one child), so c has 6 rows: every
            // product below is of fixed-size 6-vectors. G(rx_i, ry_j) += A_x,i . (X_c A_y,j),
            // mirrored for x != y.
            const double* ax = mPool.data() + px[ix].offset; // 6 x mx, column-major
            const double* ay = mPool.data() + py[iy].offset; // 6 x my
            const int* rx = mSlotRows[x].data();
            const int* ry = mSlotRows[y].data();
            for (int j = 0; j < my; ++j)
            {
                const Vec6 t = X * Eigen::Map<const Vec6>(ay + 6 * j);
                const int column = ry[j];
                for (int i = 0; i < mx; ++i)
                {
                    const double g = Eigen::Map<const Vec6>(ax + 6 * i).dot(t);
                    G(rx[i], column) += g;
                    if (y != x)
                    {
                        G(column, rx[i]) += g;
                    }
                }
            }
        }
    }
}

// Leaves the per-body and per-block maps all -1 for the next call.
void TreeSolver::clearSlotMaps()
{
    for (int body : mSlotBodies)
    {
        mSlotOfBody[static_cast<std::size_t>(body)] = -1;
    }
    for (int b : mMarked)
    {
        mDiagonalOf[static_cast<std::size_t>(b)] = -1;
    }
}

} // namespace frontier::core
