// core/joints/cylindrical.cpp: cylindrical joint, 4 rows (docs/method.md §2): slides along
// and turns about the parent's axis d_k.
//   rows 0-1: C = [d_i . (p_b - p_a), d_j . (p_b - p_a)], lever arm of a at p_b - x_a
//   rows 2-3: C = [d_i . k_b, d_j . k_b]
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writeCylindricalJoint(const Joint& joint, const JointPose& /*pose*/, const JointGeometry& g, Rows& out)
{
    const int row = writeSlidingRows(joint, g, out, 0);
    out.positionRows = 2;
    out.count = writeAxisAlignmentRows(joint, g, out, row);
}

template void writeCylindricalJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writeCylindricalJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
