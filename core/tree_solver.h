// core/tree_solver.h: the `linear` solver, block elimination in frontier order (PAPER.md §3).
//
// Glossary (PAPER.md §2-3): block b in layout order, p(b) its one later neighbour (a node's edge
// to its parent, or an edge's parent node); D_b the block's pivot after its earlier neighbours
// were eliminated; H_bp the coupling (a joint's Jacobian block for that body, or its transpose).
//   §3 step 2 (eliminate):  D_p -= H_bp^T D_b^-1 H_bp,  keeping L_b = D_b^-1 H_bp
//   §3 step 3 (back substitute): forward z_p -= L_b^T z_b; x_b = D_b^-1 z_b; backward x_b -= L_b x_p
// Node pivots stay positive definite (M plus J^T S^-1 J terms), edge pivots negative definite
// (-J D^-1 J^T), so no pivoting is needed; a pivot that vanishes means dependent or degenerate
// joint rows and is reported with the joint's name (PAPER.md §3 "Pivots"). Memory: one 6x6 pivot
// and one 6x6 coupling per block, O(n); no fill-in.
#pragma once

#include "core/impulse_solver.h"

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
    struct Factor
    {
        Mat6 chol;     // lower Cholesky factor of D_b (node) or of -D_b (edge), top-left dim x dim
        Mat6 coupling; // L_b = D_b^-1 H_bp, dim_b x dim_p
        int dim = 0;
        int parent = -1;
        bool negated = false; // edge: chol is of -D_b
    };
    void applyPivotInverse(int block, Vec6& z) const; // z <- D_b^-1 z
    void applyPivotInverse(int block, Mat6& z) const; // on 6 columns
    std::vector<Factor> mFactors;
    std::vector<Vec6> mZ; // scratch: one vector per block
    struct PathEntry
    {
        int block = 0;
        Mat6 Z; // L^-1 e_i restricted to this block: dim x 6
        Mat6 W; // D_b^-1 Z
    };
    std::vector<std::vector<PathEntry>> mPaths; // scratch: per body with extra rows
    std::vector<int> mSlotOfBody;               // scratch: body -> path slot, -1
};

} // namespace frontier::core
