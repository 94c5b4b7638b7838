// core/joints/angle.cpp: angle joint as the holonomic universal (Hooke) joint, 4 rows
// (docs/method.md §2): ball rows plus no relative twist about d_k = a1 x b2.
//   rows 0-2: C = p_b - p_a
//   row 3:    C = a1 . b2,  J = (w_b - w_a) . (b2 x a1)
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writeAngleJoint(const Joint& joint, const JointPose& /*pose*/, const JointGeometry& g, Rows& out)
{
    const int row = writeBallRows(g, out, 0);
    out.positionRows = 3;
    out.count = writeTwistRow(joint, g, out, row);
}

template void writeAngleJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writeAngleJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
