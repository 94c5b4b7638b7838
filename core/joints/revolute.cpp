// core/joints/revolute.cpp: revolute (hinge) joint, 5 rows (docs/method.md §2).
//   rows 0-2: ball, C = p_b - p_a
//   rows 3-4: the child's axis k_b stays on the parent's: C = [d_i . k_b, d_j . k_b],
//             J = (w_b - w_a) . (k_b x d_i), (w_b - w_a) . (k_b x d_j)
#include "core/joints/joint_rows.h"

namespace frontier::core::detail
{

template <class Rows>
void writeRevoluteJoint(const Joint& joint, const JointPose& /*pose*/, const JointGeometry& g, Rows& out)
{
    const int row = writeBallRows(g, out, 0);
    out.positionRows = 3;
    out.count = writeAxisAlignmentRows(joint, g, out, row);
}

template void writeRevoluteJoint(const Joint&, const JointPose&, const JointGeometry&, JointRows&);
template void writeRevoluteJoint(const Joint&, const JointPose&, const JointGeometry&, JointRowsSlot&);
} // namespace frontier::core::detail
