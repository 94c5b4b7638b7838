// core/step/impulse_memory.h: the impulses of the last step's extra rows, carried into this step
// as its starting guess (warm start; docs/method.md §5): resting contact then needs few sweeps, or
// none when the carried impulses still meet every condition.
#pragma once

#include "core/contact.h"
#include "core/extra_rows.h"
#include "core/step/row_key.h"

#include <Eigen/Dense>
#include <cstdint>
#include <utility>
#include <vector>

namespace frontier::core
{

class ImpulseMemory
{
  public:
    // The last step's impulses on this step's blocks, into lambda (set to zero by the caller, laid
    // out by the blocks): a contact between the same bodies within cWarmDistance of one of the
    // last step's starts from that one's impulse; loop and limit blocks from their joint's impulse.
    // True when some impulse was carried over.
    bool warmStart(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts,
                   Eigen::VectorXd& lambda) const;
    // Keeps this step's contacts and the impulses of its blocks for the next step.
    void remember(const std::vector<ExtraBlock>& blocks, const std::vector<Contact>& contacts,
                  const Eigen::VectorXd& lambda);

  private:
    static std::uint64_t bodyPairKey(const Contact& c);
    // Last step's contacts and their impulses (normal, two tangents; N s).
    std::vector<Contact> mPreviousContacts;
    std::vector<Vec3> mPreviousImpulses;
    // mPreviousContacts by body pair, then index: (bodyPairKey, index)
    std::vector<std::pair<std::uint64_t, int>> mPreviousOrder;
    struct JointImpulse // last step's impulse of a loop or limit block
    {
        RowKey key;
        Vec6 lambda; // N s or N m s
    };
    std::vector<JointImpulse> mPreviousJointImpulses;
};

} // namespace frontier::core
