// core/delassus.cpp: the Delassus matrix by tree, its parts and islands (docs/method.md §5).
#include "core/delassus.h"

#include <algorithm>
#include <numeric>

namespace frontier::core
{

void DelassusMatrix::layOut(const std::vector<ExtraBlock>& blocks, const std::vector<int>& treeOfBody)
{
    auto treeOf = [&](int body) { return body >= 0 ? treeOfBody[static_cast<std::size_t>(body)] : -1; };
    for (const Part& part : mParts) // the last layout's map, back to all -1
    {
        if (part.tree >= 0)
        {
            mPartOfTree[static_cast<std::size_t>(part.tree)] = -1;
        }
    }
    int trees = 0;
    mRows = 0;
    for (const ExtraBlock& block : blocks)
    {
        trees = std::max({trees, treeOf(block.bodyA) + 1, treeOf(block.bodyB) + 1});
        mRows = std::max(mRows, block.offset + block.count);
    }
    if (mPartOfTree.size() < static_cast<std::size_t>(trees))
    {
        mPartOfTree.resize(static_cast<std::size_t>(trees), -1);
    }
    // Parts in the order their trees first appear; the matrices of earlier layouts keep their
    // storage (resized below only when a part grows).
    int count = 0;
    recordRows(blocks);
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        const ExtraBlock& block = blocks[b];
        const int a = treeOf(block.bodyA);
        const int c = treeOf(block.bodyB);
        int side = 0;
        for (int tree : {a, c})
        {
            if (tree < 0 || (side == 1 && tree == a))
            {
                continue;
            }
            int& p = mPartOfTree[static_cast<std::size_t>(tree)];
            if (p < 0)
            {
                p = count++;
                if (mParts.size() < static_cast<std::size_t>(count))
                {
                    mParts.emplace_back();
                }
                Part& fresh = mParts[static_cast<std::size_t>(p)];
                fresh.tree = tree;
                fresh.blocks.clear();
                fresh.offsets.clear();
                fresh.global.clear();
                fresh.rows = 0;
            }
            Part& part = mParts[static_cast<std::size_t>(p)];
            mPlaces[b].part[side] = p;
            mPlaces[b].offset[side] = part.rows;
            part.blocks.push_back(static_cast<int>(b));
            part.offsets.push_back(part.rows);
            for (int q = 0; q < block.count; ++q)
            {
                part.global.push_back(block.offset + q);
            }
            part.rows += block.count;
            side = 1;
        }
    }
    mParts.resize(static_cast<std::size_t>(count));
    for (Part& part : mParts)
    {
        part.G.resize(part.rows, part.rows); // keeps the allocation when the size is the same
        part.free.resize(part.rows);
    }
    findIslands();
    touch();
}

void DelassusMatrix::setDense(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G)
{
    mRows = static_cast<int>(G.rows());
    for (const Part& part : mParts)
    {
        if (part.tree >= 0)
        {
            mPartOfTree[static_cast<std::size_t>(part.tree)] = -1;
        }
    }
    mParts.resize(1);
    Part& part = mParts[0];
    part.tree = -1;
    part.blocks.resize(blocks.size());
    std::iota(part.blocks.begin(), part.blocks.end(), 0);
    part.offsets.clear();
    recordRows(blocks);
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        part.offsets.push_back(blocks[b].offset);
        mPlaces[b].part[0] = 0;
        mPlaces[b].offset[0] = blocks[b].offset;
    }
    part.rows = mRows;
    part.global.resize(static_cast<std::size_t>(mRows));
    std::iota(part.global.begin(), part.global.end(), 0);
    part.G = G;
    part.free = G.diagonal(); // no masses known: the rows' own scale
    findIslands();
    touch();
}

// Union-find over the parts: a block in two parts joins them.
void DelassusMatrix::findIslands()
{
    mUnion.resize(mParts.size());
    std::iota(mUnion.begin(), mUnion.end(), 0);
    auto root = [&](int p)
    {
        while (mUnion[static_cast<std::size_t>(p)] != p)
        {
            p = mUnion[static_cast<std::size_t>(p)] =
                mUnion[static_cast<std::size_t>(mUnion[static_cast<std::size_t>(p)])];
        }
        return p;
    };
    for (const Place& place : mPlaces)
    {
        if (place.part[1] >= 0)
        {
            const int a = root(place.part[0]);
            const int b = root(place.part[1]);
            mUnion[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
        }
    }
    // Islands numbered by their first part; blocks and parts listed island by island, ascending.
    std::vector<int>& islandOfPart = mIslandPartStart; // reused as scratch below
    islandOfPart.assign(mParts.size(), -1);
    int islands = 0;
    for (std::size_t p = 0; p < mParts.size(); ++p)
    {
        const int r = root(static_cast<int>(p));
        if (islandOfPart[static_cast<std::size_t>(r)] < 0)
        {
            islandOfPart[static_cast<std::size_t>(r)] = islands++;
        }
        islandOfPart[p] = islandOfPart[static_cast<std::size_t>(r)];
    }
    mIslandOf.assign(mPlaces.size(), -1);
    mIslandStart.assign(static_cast<std::size_t>(islands) + 1, 0);
    for (std::size_t b = 0; b < mPlaces.size(); ++b)
    {
        if (mPlaces[b].part[0] >= 0)
        {
            mIslandOf[b] = islandOfPart[static_cast<std::size_t>(mPlaces[b].part[0])];
            ++mIslandStart[static_cast<std::size_t>(mIslandOf[b]) + 1];
        }
    }
    std::partial_sum(mIslandStart.begin(), mIslandStart.end(), mIslandStart.begin());
    mIslandBlocks.resize(static_cast<std::size_t>(mIslandStart.back()));
    std::vector<int> cursor(mIslandStart.begin(), mIslandStart.end() - 1);
    for (std::size_t b = 0; b < mPlaces.size(); ++b)
    {
        if (mIslandOf[b] >= 0)
        {
            mIslandBlocks[static_cast<std::size_t>(cursor[static_cast<std::size_t>(mIslandOf[b])]++)] =
                static_cast<int>(b);
        }
    }
    std::vector<int> partStart(static_cast<std::size_t>(islands) + 1, 0);
    for (std::size_t p = 0; p < mParts.size(); ++p)
    {
        ++partStart[static_cast<std::size_t>(islandOfPart[p]) + 1];
    }
    std::partial_sum(partStart.begin(), partStart.end(), partStart.begin());
    mIslandParts.resize(mParts.size());
    std::vector<int> partCursor(partStart.begin(), partStart.end() - 1);
    for (std::size_t p = 0; p < mParts.size(); ++p)
    {
        mIslandParts[static_cast<std::size_t>(partCursor[static_cast<std::size_t>(islandOfPart[p])]++)] =
            static_cast<int>(p);
    }
    mIslandPartStart = std::move(partStart);
}

void DelassusMatrix::recordRows(const std::vector<ExtraBlock>& blocks)
{
    mPlaces.assign(blocks.size(), Place{});
    mBlockOfRow.assign(static_cast<std::size_t>(mRows), -1);
    mBlockRows.resize(2 * blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        std::fill_n(mBlockOfRow.begin() + blocks[b].offset, blocks[b].count, static_cast<int>(b));
        mBlockRows[2 * b] = blocks[b].offset;
        mBlockRows[2 * b + 1] = blocks[b].count;
    }
}

int DelassusMatrix::localRow(int p, int r) const
{
    const std::size_t b = static_cast<std::size_t>(mBlockOfRow[static_cast<std::size_t>(r)]);
    const Place& place = mPlaces[b];
    return place.offset[place.part[0] == p ? 0 : 1] + (r - mBlockRows[2 * b]);
}

double DelassusMatrix::entry(int r, int s) const
{
    const Place& a = mPlaces[static_cast<std::size_t>(mBlockOfRow[static_cast<std::size_t>(r)])];
    const Place& b = mPlaces[static_cast<std::size_t>(mBlockOfRow[static_cast<std::size_t>(s)])];
    double sum = 0.0;
    for (int p : a.part)
    {
        if (p >= 0 && (b.part[0] == p || b.part[1] == p))
        {
            sum += mParts[static_cast<std::size_t>(p)].G(localRow(p, r), localRow(p, s));
        }
    }
    return sum;
}

void DelassusMatrix::diagonalBlock(int block, int count, Mat6& out) const
{
    out.topLeftCorner(count, count).setZero();
    const Place& place = mPlaces[static_cast<std::size_t>(block)];
    for (int side = 0; side < 2; ++side)
    {
        if (place.part[side] >= 0)
        {
            const int o = place.offset[side];
            out.topLeftCorner(count, count) +=
                mParts[static_cast<std::size_t>(place.part[side])].G.block(o, o, count, count);
        }
    }
}

double DelassusMatrix::freeScale(int block, int count) const
{
    const Place& place = mPlaces[static_cast<std::size_t>(block)];
    double largest = 0.0;
    for (int q = 0; q < count; ++q)
    {
        double sum = 0.0;
        for (int side = 0; side < 2; ++side)
        {
            if (place.part[side] >= 0)
            {
                sum += mParts[static_cast<std::size_t>(place.part[side])].free(place.offset[side] + q);
            }
        }
        largest = std::max(largest, sum);
    }
    return largest;
}

void DelassusMatrix::toDense(Eigen::MatrixXd& out, int rows) const
{
    const int n = std::max(rows, mRows);
    out.setZero(n, n);
    for (const Part& part : mParts)
    {
        for (int j = 0; j < part.rows; ++j)
        {
            const int column = part.global[static_cast<std::size_t>(j)];
            for (int i = 0; i < part.rows; ++i)
            {
                out(part.global[static_cast<std::size_t>(i)], column) += part.G(i, j);
            }
        }
    }
}

void DelassusMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& out) const
{
    out.setZero(mRows);
    Eigen::VectorXd local, product;
    for (const Part& part : mParts)
    {
        local.resize(part.rows);
        for (int l = 0; l < part.rows; ++l)
        {
            local(l) = x(part.global[static_cast<std::size_t>(l)]);
        }
        product.noalias() = part.G * local;
        for (int l = 0; l < part.rows; ++l)
        {
            out(part.global[static_cast<std::size_t>(l)]) += product(l);
        }
    }
}

void DelassusMatrix::gather(const std::vector<ExtraBlock>& blocks, const std::vector<int>& treeOfBody,
                            const DelassusMatrix& from, const std::vector<int>& fromRow)
{
    layOut(blocks, treeOfBody);
    std::vector<int> local; // per local row of a part: its local row in from's part of the tree
    for (Part& part : mParts)
    {
        const int source = from.partOfTree(part.tree);
        local.resize(static_cast<std::size_t>(part.rows));
        for (int l = 0; l < part.rows; ++l)
        {
            const int row = part.global[static_cast<std::size_t>(l)];
            local[static_cast<std::size_t>(l)] =
                from.localRow(source, fromRow[static_cast<std::size_t>(row)]);
        }
        const Eigen::MatrixXd& G = from.part(source).G;
        for (int j = 0; j < part.rows; ++j)
        {
            part.free(j) = from.part(source).free(local[static_cast<std::size_t>(j)]);
            for (int i = 0; i < part.rows; ++i)
            {
                part.G(i, j) = G(local[static_cast<std::size_t>(i)], local[static_cast<std::size_t>(j)]);
            }
        }
    }
    touch();
}

} // namespace frontier::core
