// core/joints/planar.cpp: planar joint, 3 rows (docs/method.md §2): the child slides in the plane
// through the anchor normal to the parent's axis d_k and turns about d_k.
//   row 0:    C = d_k . (p_b - p_a), lever arm of a at p_b - x_a
//   rows 1-2: C = [d_i . k_b, d_j . k_b]
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writePlanarJoint(const Joint& joint, const JointPose& /*pose*/, const JointGeometry& g, Rows& out)
{
    const int row = writeSlidingRow(joint.axisParent, g, out, 0);
    out.positionRows = 1;
    out.count = writeAxisAlignmentRows(joint, g, out, row);
}

template void writePlanarJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writePlanarJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
