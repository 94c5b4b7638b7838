// collision/filter.h: public API of the collision pair rule (docs/method.md §10). The detector
// and the stability suite's barrier watch both ask it, so the rule is written once.
#pragma once

#include "core/model.h"

#include <cstdint>
#include <vector>

namespace frontier::collision
{

// Which body pairs may collide (docs/method.md §10): not two static bodies, not two bodies of one
// non-empty group, not the pairs in contact.ignore, not bodies joined by a joint unless the
// joint says collideConnected. Memory O(bodies + joints + ignore pairs).
class PairFilter
{
  public:
    explicit PairFilter(const core::Model& model);

    bool allowed(int a, int b) const;
    bool isStatic(int body) const { return mStatic[static_cast<std::size_t>(body)] != 0; }
    int bodyCount() const { return static_cast<int>(mStatic.size()); }

    // The number of allowed pairs (a, b), a < b, among the bodies with among[body] != 0, counted
    // without listing them: O(bodies + joints + ignore pairs) time and memory.
    long long allowedPairCount(const std::vector<char>& among) const;

    // Per body: whether it is among[] and may collide with at least one other body among them;
    // O(bodies + joints + ignore pairs), counted as in allowedPairCount.
    std::vector<char> hasAllowedPartner(const std::vector<char>& among) const;

  private:
    // Bodies of `among`: how many, how many static, and both per group.
    struct MemberCounts
    {
        long long members = 0;
        long long statics = 0;
        std::vector<long long> groupMembers;
        std::vector<long long> groupStatics;
    };
    MemberCounts countMembers(const std::vector<char>& among) const;
    static std::uint64_t key(int a, int b);
    bool excludedByRule(std::size_t a, std::size_t b) const;

    std::vector<char> mStatic;            // per body
    std::vector<int> mGroup;              // per body, -1 for none
    std::vector<int> mGroupSize;          // per group id
    std::vector<std::uint64_t> mExcluded; // sorted keys of (min, max) pairs
};

} // namespace frontier::collision
