// core/joints/prismatic.cpp: prismatic (slider) joint, 5 rows (docs/method.md §2).
//   rows 0-1: C = [d_i . (p_b - p_a), d_j . (p_b - p_a)], lever arm of a at p_b - x_a
//   rows 2-4: no relative rotation, C = rotation vector of q_b (q_a q_rest)^-1, J = w_b - w_a
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writePrismaticJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, Rows& out)
{
    const int row = writeSlidingRows(joint, g, out, 0);
    out.positionRows = 2;
    out.count = writeWeldRotationRows(joint, pose, out, row);
}

template void writePrismaticJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writePrismaticJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
