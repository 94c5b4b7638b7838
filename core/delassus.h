// core/delassus.h: the Delassus matrix G = J_x H^-1 J_x^T of the extra rows (docs/method.md §5),
// stored by tree.
//
// The joints pass impulses along a tree and never across, so H is block diagonal by tree and
//     G = sum over trees t of J_t H_t^-1 J_t^T,
// J_t the extra rows' parts on the bodies of tree t. The rows that touch tree t (a contact between
// two trees touches both) form the *part* of t, which holds the term J_t H_t^-1 J_t^T dense on
// those rows (the inverse of a connected tree's matrix is dense). Two rows with no tree in common
// have G_rs = 0 exactly and are stored nowhere: a pile of separate bodies costs the sum of its
// trees' squares, not the square of the whole, and a tree whose rows did not change keeps its part
// (core/step/contact_problem.h). Parts joined by a row that touches both form an *island*: islands
// are independent problems, each solved to its own stopping test (core/extra_rows.h).
#pragma once

#include "core/extra_rows.h"

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

namespace frontier::core
{

class DelassusMatrix
{
  public:
    struct Part
    {
        int tree = -1;            // FrontierLayout::treeOfBody; -1: one part for every row (setDense)
        std::vector<int> blocks;  // the blocks with a body on the tree, ascending
        std::vector<int> offsets; // per entry of `blocks`, its first row within the part
        std::vector<int> global;  // per row of the part, its row in G
        int rows = 0;
        Eigen::MatrixXd G;    // rows x rows, column-major: the tree's term of G on these rows
        Eigen::VectorXd free; // per row: its term without the joints, J_t M_t^-1 J_t^T (its scale)
    };
    // Where a block sits: in one part per tree it touches (at most two), at a first row in each.
    struct Place
    {
        int part[2] = {-1, -1};
        int offset[2] = {0, 0};
    };

    // The parts and islands of laid-out blocks (layoutExtraRows), from each body's tree (-1 for a
    // static body). A part's matrix is sized, its values left to the caller
    // (ImpulseSolver::delassus). A block with no moving body belongs to no part.
    void layOut(const std::vector<ExtraBlock>& blocks, const std::vector<int>& treeOfBody);
    // One part holding every row, its matrix the dense G given (rows x rows): tests, and small
    // problems given whole.
    void setDense(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G);

    int parts() const { return static_cast<int>(mParts.size()); }
    Part& part(int p) { return mParts[static_cast<std::size_t>(p)]; }
    const Part& part(int p) const { return mParts[static_cast<std::size_t>(p)]; }
    const Place& place(int block) const { return mPlaces[static_cast<std::size_t>(block)]; }
    int rows() const { return mRows; }
    // The part of a tree, -1 when no row touches it.
    int partOfTree(int tree) const
    {
        return tree >= 0 && static_cast<std::size_t>(tree) < mPartOfTree.size()
                   ? mPartOfTree[static_cast<std::size_t>(tree)]
                   : -1;
    }

    int islands() const { return static_cast<int>(mIslandStart.size()) - 1; }
    // The blocks of island i, ascending.
    std::span<const int> islandBlocks(int i) const
    {
        const auto first = static_cast<std::size_t>(mIslandStart[static_cast<std::size_t>(i)]);
        const auto last = static_cast<std::size_t>(mIslandStart[static_cast<std::size_t>(i) + 1]);
        return {mIslandBlocks.data() + first, last - first};
    }
    int islandOfBlock(int block) const { return mIslandOf[static_cast<std::size_t>(block)]; }
    // The parts of island i.
    std::span<const int> islandParts(int i) const
    {
        const auto first = static_cast<std::size_t>(mIslandPartStart[static_cast<std::size_t>(i)]);
        const auto last = static_cast<std::size_t>(mIslandPartStart[static_cast<std::size_t>(i) + 1]);
        return {mIslandParts.data() + first, last - first};
    }

    // The block whose rows hold global row r.
    int blockOfRow(int r) const { return mBlockOfRow[static_cast<std::size_t>(r)]; }
    // G_rs of global rows (0 when they share no part).
    double entry(int r, int s) const;
    // The block's diagonal block of G (count x count top-left of `out`), summed over its parts.
    void diagonalBlock(int block, int count, Mat6& out) const;
    // The largest of the block's rows' values without the joints (Part::free, summed over its parts):
    // the scale of its pivots.
    double freeScale(int block, int count) const;
    // The whole matrix, dense (rows x rows; at least rows(), zero beyond).
    void toDense(Eigen::MatrixXd& out, int rows = 0) const;
    // out = G x (rows, for the rows of every part).
    void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& out) const;
    // This matrix on a subset of the rows of `from` (laid out as `blocks`, of which row r is row
    // fromRow[r] of `from`): each part of the new layout takes the entries of the part of `from`
    // on the same tree.
    void gather(const std::vector<ExtraBlock>& blocks, const std::vector<int>& treeOfBody,
                const DelassusMatrix& from, const std::vector<int>& fromRow);

    // Counts the changes of layout and values, so that what is computed from the matrix (the
    // Gauss-Seidel's pivots) can tell whether it still holds; touch() after changing a part's
    // values.
    std::uint64_t version() const { return mVersion; }
    void touch() { mVersion = ++sVersions; }

  private:
    // Local row of global row r in part p (r must be in it).
    int localRow(int p, int r) const;
    void recordRows(const std::vector<ExtraBlock>& blocks);
    void findIslands();

    std::vector<Part> mParts;
    std::vector<Place> mPlaces;     // per block
    std::vector<int> mBlockOfRow;   // per global row
    std::vector<int> mBlockRows;    // per block: its first global row, then its row count
    std::vector<int> mPartOfTree;   // per tree, its part or -1
    std::vector<int> mIslandStart;  // islands' first entries in mIslandBlocks, and one past the last
    std::vector<int> mIslandBlocks; // blocks by island, ascending within each
    std::vector<int> mIslandOf;     // per block, -1 for a block in no part
    std::vector<int> mIslandPartStart;
    std::vector<int> mIslandParts;
    std::vector<int> mUnion; // scratch: union-find over parts
    int mRows = 0;
    std::uint64_t mVersion = 0;
    // Versions are unique across matrices (they share the Gauss-Seidel's scratch) and threads.
    static inline std::atomic<std::uint64_t> sVersions{0};
};

} // namespace frontier::core
