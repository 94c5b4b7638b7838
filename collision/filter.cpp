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
    mExcludedDegree.assign(n, 0);

    std::map<std::string, int> groupIds;
    for (std::size_t i = 0; i < n; ++i)
    {
        const core::Body& body = model.bodies[i];
        if (body.isStatic)
        {
            mStatic[i] = 1;
            ++mStaticCount;
        }
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
        ++mExcludedDegree[static_cast<std::size_t>(a)];
        ++mExcludedDegree[static_cast<std::size_t>(b)];
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

int PairFilter::excludedBound(int body) const
{
    const auto i = static_cast<std::size_t>(body);
    int bound = mExcludedDegree[i];
    if (mGroup[i] >= 0)
        bound += mGroupSize[static_cast<std::size_t>(mGroup[i])] - 1;
    if (mStatic[i])
        bound += mStaticCount - 1;
    return bound;
}

long long PairFilter::allowedPairCount(const std::vector<char>& among) const
{
    // All pairs, less those of two static bodies or of one group (counted by inclusion-exclusion:
    // a pair of two static bodies of one group is in both), less the excluded pairs that neither
    // rule already removed.
    auto pairs = [](long long k) { return k * (k - 1) / 2; };
    long long members = 0;
    long long statics = 0;
    std::vector<long long> groupMembers(mGroupSize.size(), 0);
    std::vector<long long> groupStatics(mGroupSize.size(), 0);
    for (std::size_t i = 0; i < mStatic.size(); ++i)
    {
        if (!among[i])
            continue;
        ++members;
        statics += mStatic[i] ? 1 : 0;
        if (mGroup[i] >= 0)
        {
            ++groupMembers[static_cast<std::size_t>(mGroup[i])];
            groupStatics[static_cast<std::size_t>(mGroup[i])] += mStatic[i] ? 1 : 0;
        }
    }
    long long count = pairs(members) - pairs(statics);
    for (std::size_t g = 0; g < groupMembers.size(); ++g)
        count -= pairs(groupMembers[g]) - pairs(groupStatics[g]);
    for (const std::uint64_t k : mExcluded)
    {
        const auto a = static_cast<std::size_t>(k >> 32);
        const auto b = static_cast<std::size_t>(k & 0xffffffffu);
        if (!among[a] || !among[b] || (mStatic[a] && mStatic[b]) ||
            (mGroup[a] >= 0 && mGroup[a] == mGroup[b]))
            continue;
        --count;
    }
    return count;
}

} // namespace frontier::collision
