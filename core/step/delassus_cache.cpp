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
    for (int p = 0; p < mMemory.g.parts(); ++p)
    {
        if (mMemory.state[static_cast<std::size_t>(p)] == PartState::Empty)
        {
            keep(p);
        }
    }
    std::swap(mMemory.g, mMemory.last);
    std::swap(mMemory.records, mMemory.lastRecords);
    mBlocks = &blocks;
    mMemory.g.layOut(blocks, mLayout.treeOfBody);
    mMemory.keys.resize(blocks.size());
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        mMemory.keys[b] = rowKey(blocks[b], contacts);
    }
    mMemory.records.resize(static_cast<std::size_t>(mMemory.g.parts()));
    for (Record& record : mMemory.records)
    {
        record.builtStep = -1;
    }
    mMemory.state.assign(static_cast<std::size_t>(mMemory.g.parts()), PartState::Empty);
    mBuiltAny = false;
    ++mMemory.step;
}

bool DelassusCache::flagged(std::span<const std::uint8_t> islands, int part) const
{
    if (islands.empty())
    {
        return true;
    }
    const int block = mMemory.g.part(part).blocks.front();
    return islands[static_cast<std::size_t>(mMemory.g.islandOfBlock(block))] != 0;
}

// The last step's part of the same tree, when it has values for the same rows (in the same order)
// and is recent: its values move into this step's part.
bool DelassusCache::keep(int p)
{
    DelassusMatrix::Part& part = mMemory.g.part(p);
    const int q = mMemory.last.partOfTree(part.tree);
    if (q < 0)
    {
        return false;
    }
    Record& last = mMemory.lastRecords[static_cast<std::size_t>(q)];
    if (last.builtStep < 0 || mMemory.step - last.builtStep > cMaxAge ||
        last.keys.size() != part.blocks.size())
    {
        return false;
    }
    for (std::size_t k = 0; k < part.blocks.size(); ++k)
    {
        if (!sameRow(mMemory.keys[static_cast<std::size_t>(part.blocks[k])], last.keys[k], cReuseDistance,
                     cReuseTurn))
        {
            return false;
        }
    }
    std::swap(part.G, mMemory.last.part(q).G); // the same rows: the same size
    std::swap(part.free, mMemory.last.part(q).free);
    std::swap(mMemory.records[static_cast<std::size_t>(p)], last);
    last.builtStep = -1; // its values have moved
    mMemory.state[static_cast<std::size_t>(p)] = PartState::Kept;
    return true;
}

// Values of the listed parts from this step's factorization; their records name this step.
void DelassusCache::build(std::span<const int> parts)
{
    if (parts.empty())
    {
        return;
    }
    mSolver.delassusParts(*mBlocks, mMemory.g, parts);
    for (int p : parts)
    {
        Record& record = mMemory.records[static_cast<std::size_t>(p)];
        const DelassusMatrix::Part& part = mMemory.g.part(p);
        record.keys.resize(part.blocks.size());
        for (std::size_t k = 0; k < part.blocks.size(); ++k)
        {
            record.keys[k] = mMemory.keys[static_cast<std::size_t>(part.blocks[k])];
        }
        record.builtStep = mMemory.step;
        mMemory.state[static_cast<std::size_t>(p)] = PartState::Built;
    }
    mBuiltAny = true;
}

void DelassusCache::prepare(std::span<const std::uint8_t> islands, bool reuse)
{
    mToBuild.clear();
    bool kept = false;
    for (int p = 0; p < mMemory.g.parts(); ++p)
    {
        if (mMemory.state[static_cast<std::size_t>(p)] != PartState::Empty || !flagged(islands, p))
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
        mMemory.g.touch(); // kept values arrived after the layout
    }
}

void DelassusCache::rebuild(std::span<const std::uint8_t> islands)
{
    mToBuild.clear();
    for (int p = 0; p < mMemory.g.parts(); ++p)
    {
        if (mMemory.state[static_cast<std::size_t>(p)] == PartState::Kept && flagged(islands, p))
        {
            mToBuild.push_back(p);
        }
    }
    build(mToBuild);
}

bool DelassusCache::exact(int island) const
{
    for (int p : mMemory.g.islandParts(island))
    {
        if (mMemory.state[static_cast<std::size_t>(p)] != PartState::Built)
        {
            return false;
        }
    }
    return true;
}

void DelassusCache::restore(const Memory& memory)
{
    mMemory = memory;
    mBuiltAny = false;
}

bool DelassusCache::complete() const
{
    return std::none_of(mMemory.state.begin(), mMemory.state.end(),
                        [](PartState s) { return s == PartState::Empty; });
}

} // namespace frontier::core
