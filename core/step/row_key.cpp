// core/step/row_key.cpp: keys of extra blocks across steps.
#include "core/step/row_key.h"

namespace frontier::core
{

RowKey rowKey(const ExtraBlock& block, const std::vector<Contact>& contacts)
{
    RowKey key{block.kind,   block.count,    block.bodyA,  block.bodyB,
               block.source, block.actuator, Vec3::Zero(), Vec6::Zero()};
    if (block.kind == ExtraBlock::Kind::Contact)
    {
        const Contact& c = contacts[static_cast<std::size_t>(block.source)];
        key.source = -1; // contact indices are not stable; the point and normal are compared
        key.point_W = c.point_W;
        key.direction.head<3>() = c.normal_W;
    }
    else
    {
        // Loops and limits by joint; the first row tells which side a limit is on (its sign
        // flips between the lower and the upper limit).
        key.direction = (block.bodyA >= 0 ? block.J_A : block.J_B).row(0).transpose();
    }
    return key;
}

bool sameJointRows(const RowKey& now, const RowKey& then)
{
    return now.kind == then.kind && now.source == then.source && now.actuator == then.actuator &&
           now.direction.dot(then.direction) > 0.0;
}

} // namespace frontier::core
