// core/tree_solver.h: the `linear` solver, block elimination in frontier order (docs/method.md §3).
//
// Glossary (docs/method.md §1-3): block b in layout order, p(b) its one later neighbour (a node's edge
// to its parent, or an edge's parent node); D_b the block's pivot after its earlier neighbours
// were eliminated; H_bp the coupling (a joint's Jacobian block for that body, or its transpose).
//   §3 step 2 (eliminate):  D_p -= H_bp^T D_b^-1 H_bp,  keeping L_b = D_b^-1 H_bp
//   §3 step 3 (back substitute): forward z_p -= L_b^T z_b; x_b = D_b^-1 z_b; backward x_b -= L_b x_p
// Node pivots stay positive definite (M plus J^T S^-1 J terms), edge pivots negative definite
// (-J D^-1 J^T, minus the compliance of drive rows, core/joints/drive.h), so no pivoting is needed; a pivot
// that vanishes means dependent or degenerate joint rows and is reported with the joint's name
// (docs/method.md §3 "Pivots").
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
    // One pass fewer over the factors: the forward sweep runs block by block with the
    // elimination, while each block's factors are still in cache.
    void factorAndSolve(const RowSystem& system, const BlockVector& rhs, BlockVector& solution) override;
    const char* name() const override { return "linear"; }

    // A part of G = J_x H^-1 J_x^T without one O(n) solve per row (core/tree_delassus.cpp): each
    // body x of the part's tree with extra rows sends its stacked rows J_x^T up the forward sweep,
    // which reaches only the blocks on x's path to its root (A_x = L^-1 J_x^T there). Two bodies'
    // paths meet at a block c and share everything above it, so G_xy = A_x,c^T X_c A_y,c with X_c
    // the diagonal block of H^-1 at c, computed top-down for the blocks on those paths
    // (X_c = D_c^-1 + L_c X_p L_c^T, selected inversion). Cost: O(sum of path lengths) sweeps plus
    // one small product per pair of the tree's bodies.
    void delassusParts(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G,
                       std::span<const int> parts) override;

  private:
    // One block in layout order (16 bytes, so the sweeps read little besides the factors).
    struct BlockInfo
    {
        int parent = -1;                // layout index of p(b), -1 for the last block of a tree
        int index = 0;                  // body (node) or joint (edge) index
        std::uint32_t parentOffset = 0; // mOffsets[parent]: its address without a random load
        std::uint8_t dim = 0;
        std::uint8_t parentDim = 0; // 0 without a parent
        std::uint8_t flags = 0;     // the c* bits below
        std::uint8_t unused = 0;
    };
    void layOutBlocks(const FrontierLayout& layout); // the block table and arena offsets
    void eliminateAll(const RowSystem& system, const BlockVector* rhs);
    void eliminate(std::size_t block);                           // §3 step 2 at one block
    void forwardStep(std::size_t block, const BlockVector& rhs); // §3 step 3, forward, one block
    void backwardSweep(BlockVector& solution);                   // §3 step 3, backward
    // The steps of delassusParts(), in order, for one part (core/tree_delassus.cpp).
    template <typename F>
    void forEachSide(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part, F&& f) const;
    void gatherSlots(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part);
    void layOutPaths();
    void placeJacobians(const std::vector<ExtraBlock>& blocks, const DelassusMatrix::Part& part);
    void sweepPathsForward();
    void invertOnPaths();
    void assembleDelassus(Eigen::MatrixXd& G);
    void clearSlotMaps();

    static constexpr std::uint8_t cEdge = 1;              // a joint block; its pivot factor is of -D_b
    static constexpr std::uint8_t cHasChildren = 2;       // some earlier block has this one as parent
    static constexpr std::uint8_t cFirstChild = 4;        // the first (in layout order) child of its parent
    static constexpr std::uint8_t cChildIsJointChild = 8; // edge: its child node is the joint's child
                                                          // body (LayoutBlock::childIsJointChild)
    static constexpr std::uint8_t cDriven = 16;           // edge: ends with compliant drive rows

    LargeVector<BlockInfo> mBlocks;    // layout order
    std::uint64_t mBlocksOfLayout = 0; // FrontierLayout::id the table was laid out for (0: none)
    // Block b's factors start at mArena[mOffsets[b]]: the lower Cholesky factor of D_b (edges:
    // of -D_b) packed by columns with reciprocal diagonal, dim (dim + 1) / 2 doubles; then
    // L_b = D_b^-1 H_bp, dim x parentDim column-major.
    LargeVector<std::uint32_t> mOffsets;
    LargeVector<double> mArena;       // huge pages at large n (core/large_vector.h)
    LargeVector<Vec6> mZ;             // scratch: one vector per block
    std::vector<std::uint8_t> mSeen;  // scratch: per block, a child was met
    std::vector<int> mUnmappedBodies; // bodies without a block (static): zero in a solution
    std::vector<int> mUnmappedJoints; // joints without a block (loops): zero in a solution
    // Scratch of delassusParts(), kept so that stepping does not allocate once sizes have settled.
    struct PathEntry
    {
        int block = 0;
        std::uint32_t offset = 0; // A_x at this block: dim x (rows of x), column-major, in mPool
    };
    std::vector<int> mSlotBodies;               // bodies with extra rows
    std::vector<int> mSlotOfBody;               // body -> slot, -1
    std::vector<std::vector<int>> mSlotRows;    // part rows of each slot's body, in stacking order
    std::vector<int> mSlotColumn;               // scratch: column cursor per slot
    std::vector<std::vector<PathEntry>> mPaths; // per slot: its node up to its root
    std::vector<double> mPool;                  // the A_x blocks of every path
    std::vector<int> mDiagonalOf;               // block -> index in mDiagonal, -1 (kept all -1)
    std::vector<int> mMarked;                   // blocks on some path, descending
    std::vector<Mat6> mDiagonal;                // X_c, dim x dim top-left, per marked block
};

} // namespace frontier::core
