// core/joints/ball.cpp: point-to-point (ball) joint, 3 rows; the nail joint is the same rows
// with the world as parent (docs/method.md §2).
//   C = p_b - p_a,  J_a = [-1, [r_a]x],  J_b = [1, -[r_b]x]
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writeBallJoint(const Joint& /*joint*/, const JointPose& /*pose*/, const JointGeometry& g, Rows& out)
{
    out.positionRows = 3;
    out.count = writeBallRows(g, out, 0);
}

template void writeBallJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writeBallJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
