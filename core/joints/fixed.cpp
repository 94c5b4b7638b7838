// core/joints/fixed.cpp: fixed joint (weld; not in the paper), 6 rows.
//   rows 0-2: C = p_b - p_a;  rows 3-5: no relative rotation, J = w_b - w_a
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writeFixedJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out)
{
    const int row = writeBallRows(g, out, 0);
    out.positionRows = 3;
    out.count = writeWeldRotationRows(joint, pose, out, row);
}

template void writeFixedJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writeFixedJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
