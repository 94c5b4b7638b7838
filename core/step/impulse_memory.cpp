// core/step/impulse_memory.cpp: warm start of the extra rows from the last step's impulses.
#include "core/step/impulse_memory.h"

#include <algorithm>

namespace frontier::core
{

bool ImpulseMemory::warmStart(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts,
                              Eigen::VectorXd& lambda) const
{
    bool any = false;
    constexpr double cWarmDistance = 5e-3; // m
    for (const ExtraBlock& block : blocks)
    {
        if (block.kind != ExtraBlock::Kind::Contact)
        {
            // Loops and limits by joint, a limit only on the same side as last step.
            const RowKey key = rowKey(block, contacts);
            for (const JointImpulse& previous : mPreviousJointImpulses)
            {
                if (sameJointRows(key, previous.key))
                {
                    lambda.segment(block.offset, block.count) = previous.lambda.head(block.count);
                    any = any || previous.lambda.head(block.count).cwiseAbs().maxCoeff() > 0.0;
                    break;
                }
            }
            continue;
        }
        const Contact& c = contacts[static_cast<std::size_t>(block.source)];
        double best = cWarmDistance * cWarmDistance;
        int match = -1;
        // The last step's contacts of the same body pair (mPreviousOrder: by pair, then index).
        const std::uint64_t pair = bodyPairKey(c);
        const auto first = std::lower_bound(mPreviousOrder.begin(), mPreviousOrder.end(),
                                            std::pair<std::uint64_t, int>(pair, -1));
        for (auto it = first; it != mPreviousOrder.end() && it->first == pair; ++it)
        {
            const std::size_t p = static_cast<std::size_t>(it->second);
            const Contact& q = mPreviousContacts[p];
            const double d = (q.point_W - c.point_W).squaredNorm();
            if (d < best && q.normal_W.dot(c.normal_W) > 0.99)
            {
                best = d;
                match = static_cast<int>(p);
            }
        }
        if (match >= 0)
        {
            lambda.segment(block.offset, block.count) =
                mPreviousImpulses[static_cast<std::size_t>(match)].head(block.count);
            any = any || lambda(block.offset) > 0.0;
        }
    }
    return any;
}

std::uint64_t ImpulseMemory::bodyPairKey(const Contact& c)
{
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.bodyA)) << 32) |
           static_cast<std::uint32_t>(c.bodyB);
}

void ImpulseMemory::remember(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts,
                             const Eigen::VectorXd& lambda)
{
    mPreviousContacts = contacts;
    mPreviousOrder.resize(contacts.size());
    for (std::size_t k = 0; k < contacts.size(); ++k)
    {
        mPreviousOrder[k] = {bodyPairKey(contacts[k]), static_cast<int>(k)};
    }
    std::sort(mPreviousOrder.begin(), mPreviousOrder.end()); // by pair, then index
    mPreviousImpulses.assign(contacts.size(), Vec3::Zero());
    mPreviousJointImpulses.clear();
    for (const ExtraBlock& block : blocks)
    {
        if (block.kind == ExtraBlock::Kind::Contact)
        {
            mPreviousImpulses[static_cast<std::size_t>(block.source)].head(block.count) =
                lambda.segment(block.offset, block.count);
        }
        else
        {
            JointImpulse previous{rowKey(block, contacts), Vec6::Zero()};
            previous.lambda.head(block.count) = lambda.segment(block.offset, block.count);
            mPreviousJointImpulses.push_back(previous);
        }
    }
}

} // namespace frontier::core
