// collision/filter.cpp: which body pairs may collide (docs/method.md §10).
#include "collision/filter.h"

#include <algorithm>
#include <map>
#include <string>

namespace frontier::collision
{

std::uint64_t PairFilter::key(int a, int b)
{
    const auto lo = static_cast<std::uint32_t>(std::min(a, b));
    const auto hi = static_cast<std::uint32_t>(std::max(a, b));
    return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

PairFilter::PairFilter(const core::Model& model)
{
    const std::size_t n = model.bodies.size();
    mStatic.assign(n, 0);
    mGroup.assign(n, -1);

    std::map<std::string, int> groupIds;
    for (std::size_t i = 0; i < n; ++i)
    {
        const core::Body& body = model.bodies[i];
        if (body.isStatic)
            mStatic[i] = 1;
        if (!body.group.empty())
        {
            const auto [it, inserted] = groupIds.emplace(body.group, static_cast<int>(groupIds.size()));
            if (inserted)
                mGroupSize.push_back(0);
            mGroup[i] = it->second;
            ++mGroupSize[static_cast<std::size_t>(it->second)];
        }
    }

    const int count = static_cast<int>(n);
    auto exclude = [&](int a, int b)
    {
        if (a < 0 || b < 0 || a >= count || b >= count || a == b)
            return;
        mExcluded.push_back(key(a, b));
    };
    for (const core::Joint& joint : model.joints)
        if (!joint.collideConnected)
            exclude(joint.parent, joint.child); // a cWorld parent is skipped by exclude()
    for (const auto& pair : model.contact.ignore)
        exclude(pair[0], pair[1]);
    std::sort(mExcluded.begin(), mExcluded.end());
    mExcluded.erase(std::unique(mExcluded.begin(), mExcluded.end()), mExcluded.end());
}

bool PairFilter::allowed(int a, int b) const
{
    if (a == b)
        return false;
    const auto ia = static_cast<std::size_t>(a);
    const auto ib = static_cast<std::size_t>(b);
    if (mStatic[ia] && mStatic[ib])
        return false;
    if (mGroup[ia] >= 0 && mGroup[ia] == mGroup[ib])
        return false;
    return !std::binary_search(mExcluded.begin(), mExcluded.end(), key(a, b));
}

// Whether the excluded pair (a, b) is also removed by the static or the group rule.
bool PairFilter::excludedByRule(std::size_t a, std::size_t b) const
{
    return (mStatic[a] && mStatic[b]) || (mGroup[a] >= 0 && mGroup[a] == mGroup[b]);
}

PairFilter::MemberCounts PairFilter::countMembers(const std::vector<char>& among) const
{
    MemberCounts c;
    c.groupMembers.assign(mGroupSize.size(), 0);
    c.groupStatics.assign(mGroupSize.size(), 0);
    for (std::size_t i = 0; i < mStatic.size(); ++i)
    {
        if (!among[i])
            continue;
        ++c.members;
        c.statics += mStatic[i] ? 1 : 0;
        if (mGroup[i] >= 0)
        {
            ++c.groupMembers[static_cast<std::size_t>(mGroup[i])];
            c.groupStatics[static_cast<std::size_t>(mGroup[i])] += mStatic[i] ? 1 : 0;
        }
    }
    return c;
}

std::vector<char> PairFilter::hasAllowedPartner(const std::vector<char>& among) const
{
    // Body b's allowed partners: the other members, less the other static ones when b is static,
    // the other members of its group (those both static and of its group counted once) and its
    // excluded partners that neither rule removes (each key is there once).
    const auto [members, statics, groupMembers, groupStatics] = countMembers(among);
    std::vector<long long> excludedPartners(mStatic.size(), 0);
    for (const std::uint64_t k : mExcluded)
    {
        const auto a = static_cast<std::size_t>(k >> 32);
        const auto b = static_cast<std::size_t>(k & 0xffffffffu);
        if (among[a] && among[b] && !excludedByRule(a, b))
        {
            ++excludedPartners[a];
            ++excludedPartners[b];
        }
    }
    std::vector<char> out(mStatic.size(), 0);
    for (std::size_t i = 0; i < mStatic.size(); ++i)
    {
        if (!among[i])
            continue;
        long long barred = excludedPartners[i] + (mStatic[i] ? statics - 1 : 0);
        if (mGroup[i] >= 0)
        {
            const auto g = static_cast<std::size_t>(mGroup[i]);
            barred += groupMembers[g] - 1 - (mStatic[i] ? groupStatics[g] - 1 : 0);
        }
        out[i] = members - 1 - barred > 0 ? 1 : 0;
    }
    return out;
}

long long PairFilter::allowedPairCount(const std::vector<char>& among) const
{
    // All pairs, less those of two static bodies or of one group (counted by inclusion-exclusion:
    // a pair of two static bodies of one group is in both), less the excluded pairs that neither
    // rule already removed.
    auto pairs = [](long long k) { return k * (k - 1) / 2; };
    const auto [members, statics, groupMembers, groupStatics] = countMembers(among);
    long long count = pairs(members) - pairs(statics);
    for (std::size_t g = 0; g < groupMembers.size(); ++g)
        count -= pairs(groupMembers[g]) - pairs(groupStatics[g]);
    for (const std::uint64_t k : mExcluded)
    {
        const auto a = static_cast<std::size_t>(k >> 32);
        const auto b = static_cast<std::size_t>(k & 0xffffffffu);
        if (!among[a] || !among[b] || excludedByRule(a, b))
            continue;
        --count;
    }
    return count;
}

} // namespace frontier::collision
