// core/step/delassus_cache.cpp: the parts of G kept across steps while their rows stay.
#include "core/step/delassus_cache.h"

#include <algorithm>
#include <utility>

namespace frontier::core
{

namespace
{

// The same row of two steps: the same kind of block on the same bodies; a contact within the
// reuse distance and turn, a joint's rows by joint and side.
bool sameRow(const RowKey& now, const RowKey& then, double distance, double turn)
{
    if (now.kind != then.kind || now.count != then.count || now.bodyA != then.bodyA ||
        now.bodyB != then.bodyB || now.source != then.source)
    {
        return false;
    }
    if (now.kind == ExtraBlock::Kind::Contact)
    {
        return (now.point_W - then.point_W).squaredNorm() <= distance * distance &&
               now.direction.dot(then.direction) >= turn;
    }
    return sameJointRows(now, then);
}

} // namespace

void DelassusCache::layOut(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts)
{
    // Parts the step before did not need (their island held without a solve) take the values of
    // the step before it, when their rows still match: a resting tree keeps its part.
    for (int p = 0; p < mG.parts(); ++p)
    {
        if (mState[static_cast<std::size_t>(p)] == PartState::Empty)
        {
            keep(p);
        }
    }
    std::swap(mG, mLast);
    std::swap(mRecords, mLastRecords);
    mBlocks = &blocks;
    mG.layOut(blocks, mLayout.treeOfBody);
    mKeys.resize(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        mKeys[b] = rowKey(blocks[b], contacts);
    }
    mRecords.resize(static_cast<std::size_t>(mG.parts()));
    for (Record& record : mRecords)
    {
        record.builtStep = -1;
    }
    mState.assign(static_cast<std::size_t>(mG.parts()), PartState::Empty);
    mBuiltAny = false;
    ++mStep;
}

bool DelassusCache::flagged(std::span<const std::uint8_t> islands, int part) const
{
    if (islands.empty())
    {
        return true;
    }
    const int block = mG.part(part).blocks.front();
    return islands[static_cast<std::size_t>(mG.islandOfBlock(block))] != 0;
}

// The last step's part of the same tree, when it has values for the same rows (in the same order)
// and is recent: its values move into this step's part.
bool DelassusCache::keep(int p)
{
    DelassusMatrix::Part& part = mG.part(p);
    const int q = mLast.partOfTree(part.tree);
    if (q < 0)
    {
        return false;
    }
    Record& last = mLastRecords[static_cast<std::size_t>(q)];
    if (last.builtStep < 0 || mStep - last.builtStep > cMaxAge || last.keys.size() != part.blocks.size())
    {
        return false;
    }
    for (std::size_t k = 0; k < part.blocks.size(); ++k)
    {
        if (!sameRow(mKeys[static_cast<std::size_t>(part.blocks[k])], last.keys[k], cReuseDistance,
                     cReuseTurn))
        {
            return false;
        }
    }
    std::swap(part.G, mLast.part(q).G); // the same rows: the same size
    std::swap(part.free, mLast.part(q).free);
    std::swap(mRecords[static_cast<std::size_t>(p)], last);
    last.builtStep = -1; // its values have moved
    mState[static_cast<std::size_t>(p)] = PartState::Kept;
    return true;
}

// Values of the listed parts from this step's factorization; their records name this step.
void DelassusCache::build(std::span<const int> parts)
{
    if (parts.empty())
    {
        return;
    }
    mSolver.delassusParts(*mBlocks, mG, parts);
    for (int p : parts)
    {
        Record& record = mRecords[static_cast<std::size_t>(p)];
        const DelassusMatrix::Part& part = mG.part(p);
        record.keys.resize(part.blocks.size());
        for (std::size_t k = 0; k < part.blocks.size(); ++k)
        {
            record.keys[k] = mKeys[static_cast<std::size_t>(part.blocks[k])];
        }
        record.builtStep = mStep;
        mState[static_cast<std::size_t>(p)] = PartState::Built;
    }
    mBuiltAny = true;
}

void DelassusCache::prepare(std::span<const std::uint8_t> islands, bool reuse)
{
    mToBuild.clear();
    bool kept = false;
    for (int p = 0; p < mG.parts(); ++p)
    {
        if (mState[static_cast<std::size_t>(p)] != PartState::Empty || !flagged(islands, p))
        {
            continue;
        }
        if (reuse && keep(p))
        {
            kept = true;
            continue;
        }
        mToBuild.push_back(p);
    }
    build(mToBuild);
    if (kept)
    {
        mG.touch(); // kept values arrived after the layout
    }
}

void DelassusCache::rebuild(std::span<const std::uint8_t> islands)
{
    mToBuild.clear();
    for (int p = 0; p < mG.parts(); ++p)
    {
        if (mState[static_cast<std::size_t>(p)] == PartState::Kept && flagged(islands, p))
        {
            mToBuild.push_back(p);
        }
    }
    build(mToBuild);
}

bool DelassusCache::exact(int island) const
{
    for (int p : mG.islandParts(island))
    {
        if (mState[static_cast<std::size_t>(p)] != PartState::Built)
        {
            return false;
        }
    }
    return true;
}

DelassusCache::Memory DelassusCache::memory() const
{
    return {mG, mLast, mRecords, mLastRecords, mState, mKeys, mStep};
}

void DelassusCache::restore(const Memory& memory)
{
    mG = memory.g;
    mLast = memory.last;
    mRecords = memory.records;
    mLastRecords = memory.lastRecords;
    mState = memory.state;
    mKeys = memory.keys;
    mStep = memory.step;
    mBuiltAny = false;
}

bool DelassusCache::complete() const
{
    return std::none_of(mState.begin(), mState.end(), [](PartState s) { return s == PartState::Empty; });
}

} // namespace frontier::core
