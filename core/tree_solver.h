// core/tree_solver.h: the `linear` solver, block elimination in frontier order (PAPER.md §3).
//
// Glossary (PAPER.md §2-3): block b in layout order, p(b) its one later neighbour (a node's edge
// to its parent, or an edge's parent node); D_b the block's pivot after its earlier neighbours
// were eliminated; H_bp the coupling (a joint's Jacobian block for that body, or its transpose).
//   §3 step 2 (eliminate):  D_p -= H_bp^T D_b^-1 H_bp,  keeping L_b = D_b^-1 H_bp
//   §3 step 3 (back substitute): forward z_p -= L_b^T z_b; x_b = D_b^-1 z_b; backward x_b -= L_b x_p
// Node pivots stay positive definite (M plus J^T S^-1 J terms), edge pivots negative definite
// (-J D^-1 J^T), so no pivoting is needed; a pivot that vanishes means dependent or degenerate
// joint rows and is reported with the joint's name (PAPER.md §3 "Pivots").
//
// Memory: O(n), no fill-in. Each block keeps only its pivot's Cholesky factor (a packed
// dim x dim lower triangle) and L_b (dim x dim_p) at their real sizes, in layout order in one
// arena that is reused across factor() calls. Because the layout is also the elimination order,
// factor() and both sweeps of solve() stream through the arena front to back (or back to
// front); only the parent-side block is touched out of order. No pass initializes pivots or
// right-hand sides: a block's first child writes them, and a block adds its own M_i or rhs when
// it is reached. solve() fuses x_b = D_b^-1 z_b into the forward sweep (z_b is final once b's
// children are in) and writes the solution during the backward sweep, so a solve is two passes.
#pragma once

#include "core/impulse_solver.h"

#include <cstdint>

namespace frontier::core
{

class TreeSolver final : public ImpulseSolver
{
  public:
    void factor(const RowSystem& system) override;
    void solve(const BlockVector& rhs, BlockVector& solution) override;
    const char* name() const override { return "linear"; }

    // G = J_x H^-1 J_x^T from partial forward sweeps: with H = L D L^T, a unit impulse on body i
    // enters the forward sweep at i's node and reaches only the blocks on i's path to its root,
    // Z_i = L^-1 e_i there. Then K_ij = sum over the blocks common to both paths of
    // Z_i^T D^-1 Z_j is the 6x6 inverse effective mass between bodies i and j, and
    // G_rs = J_r,i K_ij J_s,j^T. Cost: O(k d) sweeps plus O(k^2) products for k bodies with extra
    // rows at depth d, instead of one O(n) solve per row.
    void delassus(const std::vector<ExtraBlock>& blocks, int rows, Eigen::MatrixXd& G) override;

  private:
    // One block in layout order (12 bytes, so the sweeps read little besides the factors).
    struct BlockInfo
    {
        int parent = -1; // layout index of p(b), -1 for the last block of a tree
        int index = 0;   // body (node) or joint (edge) index
        std::uint8_t dim = 0;
        std::uint8_t parentDim = 0; // 0 without a parent
        std::uint8_t flags = 0;     // the c* bits below
        std::uint8_t unused = 0;
    };
    static constexpr std::uint8_t cEdge = 1;              // a joint block; its pivot factor is of -D_b
    static constexpr std::uint8_t cHasChildren = 2;       // some earlier block has this one as parent
    static constexpr std::uint8_t cFirstChild = 4;        // the first (in layout order) child of its parent
    static constexpr std::uint8_t cChildIsJointChild = 8; // edge: its child node is the joint's child
                                                          // body (set during factor())

    void applyPivotInverse(int block, Mat6& z) const; // top dim rows: z <- D_b^-1 z

    std::vector<BlockInfo> mBlocks; // layout order
    // Block b's factors start at mArena[mOffsets[b]]: the lower Cholesky factor of D_b (edges:
    // of -D_b) packed by columns with reciprocal diagonal, dim (dim + 1) / 2 doubles; then
    // L_b = D_b^-1 H_bp, dim x parentDim column-major.
    std::vector<std::uint32_t> mOffsets;
    std::vector<double> mArena;
    std::vector<Vec6> mZ;             // scratch: one vector per block
    std::vector<std::uint8_t> mSeen;  // scratch: per block, a child was met
    std::vector<int> mUnmappedBodies; // bodies without a block (static): zero in a solution
    std::vector<int> mUnmappedJoints; // joints without a block (loops): zero in a solution
    struct PathEntry
    {
        int block = 0;
        Mat6 Z; // L^-1 e_i restricted to this block: dim x 6
        Mat6 W; // D_b^-1 Z
    };
    std::vector<std::vector<PathEntry>> mPaths;                   // scratch: per body with extra rows
    std::vector<int> mSlotOfBody;                                 // scratch: body -> path slot, -1
    std::vector<Mat6> mK;                                         // scratch: K_xy per slot pair
    std::vector<std::vector<int>> mBodyRows;                      // scratch: G rows of each slot's body
    std::vector<Eigen::Matrix<double, Eigen::Dynamic, 6>> mBodyJ; // scratch: its stacked J rows
    Eigen::Matrix<double, Eigen::Dynamic, 6> mJK;                 // scratch: J_x K_xy
};

} // namespace frontier::core
