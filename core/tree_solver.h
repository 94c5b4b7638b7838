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

    // Partial forward substitution for one body: the forward sweep of solve() with a right-hand
    // side that is zero except for body `body`'s 6 rows `p`. Only the blocks on the body's path
    // to its root are touched; visit(blockIndex, z) receives each of them (the contact solver
    // builds its Delassus matrix from these, PAPER.md §5).
    template <typename Visit> void forwardFromBody(int body, const Vec6& p, Visit&& visit) const;

    // x^T D_b^-1 y for vectors over block b (used to assemble Delassus entries).
    double pivotInverseProduct(int block, const Vec6& x, const Vec6& y) const;
    const FrontierLayout& layout() const { return *mSystem->layout; }

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
    const RowSystem* mSystem = nullptr;
    std::vector<Factor> mFactors;
    std::vector<Vec6> mZ; // scratch: one vector per block
};

template <typename Visit> void TreeSolver::forwardFromBody(int body, const Vec6& p, Visit&& visit) const
{
    int block = mSystem->layout->bodyBlock[static_cast<std::size_t>(body)];
    Vec6 z = p;
    while (block >= 0)
    {
        visit(block, z);
        const Factor& f = mFactors[static_cast<std::size_t>(block)];
        if (f.parent < 0)
        {
            break;
        }
        Vec6 w = z;
        applyPivotInverse(block, w);
        Vec6 next = Vec6::Zero();
        const int pd = mFactors[static_cast<std::size_t>(f.parent)].dim;
        // z_p = -H_bp^T D_b^-1 z_b = -L_b^T z_b (D_b symmetric)
        next.head(pd).noalias() = -f.coupling.topLeftCorner(f.dim, pd).transpose() * z.head(f.dim);
        z = next;
        block = f.parent;
    }
}

} // namespace frontier::core
