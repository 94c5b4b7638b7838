// core/joints/joint_rows.cpp: a joint's rows by its type's writer (core/joints/joint_types.h) and the
// row pieces the types share.
#include "core/joints/joint_rows.h"

#include "core/fixed_rows.h"
#include "core/joints/joint_types.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace frontier::core
{
namespace detail
{

namespace
{
Mat3 skew(const Vec3& v)
{
    Mat3 s;
    s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return s;
}

// One angular row: (w_b - w_a) . g.
template <class Rows> void setAngularRow(Rows& out, int row, const Vec3& g)
{
    out.J_a.row(row).setZero();
    out.J_b.row(row).setZero();
    out.J_a.template block<1, 3>(row, 3) = -g.transpose();
    out.J_b.template block<1, 3>(row, 3) = g.transpose();
}
} // namespace

JointGeometry jointGeometry(const Joint& joint, const JointPose& pose)
{
    return jointGeometry(joint, pose, pose.q_a.toRotationMatrix(), pose.q_b.toRotationMatrix());
}

JointGeometry jointGeometry(const Joint& joint, const JointPose& pose, const Mat3& R_a, const Mat3& R_b)
{
    JointGeometry g;
    g.R_a = R_a;
    g.R_b = R_b;
    g.r_a = g.R_a * joint.anchorParent;
    g.r_b = g.R_b * joint.anchorChild;
    g.p_a = pose.x_a + g.r_a;
    g.p_b = pose.x_b + g.r_b;
    g.x_a = pose.x_a;
    return g;
}

// Point-to-point, docs/method.md §2 (l_ji on the right):
//   C = p_b - p_a,  J_a = [-1, [r_a]x],  J_b = [1, -[r_b]x]   (w x r = -[r]x w)
template <class Rows> int writeBallRows(const JointGeometry& g, Rows& out, int row)
{
    if (!g.conditionsOnly)
    {
        out.J_a.template block<3, 3>(row, 0) = -Mat3::Identity();
        out.J_a.template block<3, 3>(row, 3) = skew(g.r_a);
        out.J_b.template block<3, 3>(row, 0) = Mat3::Identity();
        out.J_b.template block<3, 3>(row, 3) = -skew(g.r_b);
    }
    out.error.template segment<3>(row) = g.p_b - g.p_a;
    return row + 3;
}

// Keeps the child's axis k_b on the parent's axis: C = [d_i . k_b, d_j . k_b] (docs/method.md §2
// in holonomic form). d/dt (d_i . k_b) = (w_b - w_a) . (k_b x d_i), exactly.
template <class Rows>
int writeAxisAlignmentRows(const Joint& joint, const JointGeometry& g, Rows& out, int row)
{
    const Vec3 k_b = g.R_b * joint.axisChild;
    const Vec3 d_i = g.R_a * joint.perpParent1;
    const Vec3 d_j = g.R_a * joint.perpParent2;
    setAngularRow(out, row, k_b.cross(d_i));
    setAngularRow(out, row + 1, k_b.cross(d_j));
    out.error(row) = d_i.dot(k_b);
    out.error(row + 1) = d_j.dot(k_b);
    return row + 2;
}

// The child anchor's offset along d (a direction fixed in the parent, `local` in its frame) is
// held: C = d . (p_b - p_a) (docs/method.md §2). The exact derivative puts the lever arm of body a
// at p_b - x_a, the material point of a that coincides with p_b (docs/method.md §2).
template <class Rows> int writeSlidingRow(const Vec3& local, const JointGeometry& g, Rows& out, int row)
{
    const Vec3 gap = g.p_b - g.p_a;
    const Vec3 lever_a = g.p_b - g.x_a;
    const Vec3 d = g.R_a * local;
    out.J_a.row(row).setZero();
    out.J_b.row(row).setZero();
    out.J_a.template block<1, 3>(row, 0) = -d.transpose();
    out.J_a.template block<1, 3>(row, 3) = -lever_a.cross(d).transpose();
    out.J_b.template block<1, 3>(row, 0) = d.transpose();
    out.J_b.template block<1, 3>(row, 3) = g.r_b.cross(d).transpose();
    out.error(row) = d.dot(gap);
    return row + 1;
}

// Child anchor stays on the parent's axis line: C = [d_i . (p_b - p_a), d_j . (p_b - p_a)].
template <class Rows> int writeSlidingRows(const Joint& joint, const JointGeometry& g, Rows& out, int row)
{
    row = writeSlidingRow(joint.perpParent1, g, out, row);
    return writeSlidingRow(joint.perpParent2, g, out, row);
}

// No relative rotation: C = rotation vector of q_b (q_a q_rest)^-1, rows w_b - w_a
// (exact derivative at C = 0).
template <class Rows> int writeWeldRotationRows(const Joint& joint, const JointPose& pose, Rows& out, int row)
{
    Quat e = pose.q_b * (pose.q_a * joint.restRotation_AB).conjugate();
    if (e.w() < 0.0)
    {
        e.coeffs() = -e.coeffs();
    }
    for (int k = 0; k < 3; ++k)
    {
        setAngularRow(out, row + k, Vec3::Unit(k));
    }
    out.error.template segment<3>(row) = 2.0 * e.vec();
    return row + 3;
}

// Universal (Hooke) joint, docs/method.md §2, in holonomic form: a1 fixed in a, b2 fixed in b stay
// perpendicular, C = a1 . b2, d/dt C = (w_b - w_a) . (b2 x a1).
template <class Rows> int writeTwistRow(const Joint& joint, const JointGeometry& g, Rows& out, int row)
{
    const Vec3 a1 = g.R_a * joint.perpParent1;
    const Vec3 b2 = g.R_b * joint.angleChildAxis;
    setAngularRow(out, row, b2.cross(a1));
    out.error(row) = a1.dot(b2);
    return row + 1;
}

#define FRONTIER_ROW_WRITERS(Rows)                                                                           \
    template int writeBallRows(const JointGeometry&, Rows&, int);                                            \
    template int writeAxisAlignmentRows(const Joint&, const JointGeometry&, Rows&, int);                     \
    template int writeSlidingRow(const Vec3&, const JointGeometry&, Rows&, int);                             \
    template int writeSlidingRows(const Joint&, const JointGeometry&, Rows&, int);                           \
    template int writeWeldRotationRows(const Joint&, const JointPose&, Rows&, int);                          \
    template int writeTwistRow(const Joint&, const JointGeometry&, Rows&, int);
FRONTIER_ROW_WRITERS(JointRows)
FRONTIER_ROW_WRITERS(JointRowsSlot)
#undef FRONTIER_ROW_WRITERS

} // namespace detail

JointRowsView::operator JointRows() const
{
    JointRows rows;
    rows.count = count;
    rows.constraintRows = constraintRows;
    rows.positionRows = positionRows;
    rows.J_a.topRows(J_a.rows()) = J_a.topRows(J_a.rows());
    rows.J_b.topRows(J_b.rows()) = J_b.topRows(J_b.rows());
    rows.error = error;
    rows.compliance = compliance;
    return rows;
}

void JointRowsTable::layOut(std::span<const std::uint8_t> capacity, std::span<const std::uint8_t> driveRows,
                            std::uint64_t layoutId)
{
    mLayoutId = layoutId;
    bool same = mEntries.size() == capacity.size();
    for (std::size_t k = 0; same && k < capacity.size(); ++k)
    {
        same = mEntries[k].capacity == capacity[k] && mEntries[k].driveRows == driveRows[k];
    }
    if (same)
    {
        return;
    }
    mEntries.assign(capacity.size(), Entry{});
    std::size_t offset = 0;
    for (std::size_t k = 0; k < capacity.size(); ++k)
    {
        if (capacity[k] > 6 || driveRows[k] > capacity[k])
        {
            throw std::logic_error("joint rows: a joint's block has at most 6 rows");
        }
        mEntries[k].offset = static_cast<std::uint32_t>(offset);
        mEntries[k].capacity = capacity[k];
        mEntries[k].driveRows = driveRows[k];
        offset += 13 * std::size_t{capacity[k]} + driveRows[k]; // errors, J_a, J_b, compliances
        if (offset > std::numeric_limits<std::uint32_t>::max())
        {
            throw std::length_error("joint rows: system too large");
        }
    }
    mData.assign(offset, 0.0);
}

void evaluateJoint(const Joint& joint, const JointPose& pose, bool parentMoves, JointRows& out)
{
    evaluateJoint(joint, pose, detail::jointGeometry(joint, pose), parentMoves, out);
}

template <class Rows>
void evaluateJoint(const Joint& joint, const JointPose& pose, const detail::JointGeometry& g,
                   bool parentMoves, Rows& out)
{
    jointRowWriter<Rows>(jointTypeInfo(joint.type))(joint, pose, g, out);
    out.constraintRows = out.count;
    if (!parentMoves && !g.conditionsOnly)
    {
        out.J_a.setZero();
    }
}

template void evaluateJoint(const Joint&, const JointPose&, const detail::JointGeometry&, bool, JointRows&);
template void evaluateJoint(const Joint&, const JointPose&, const detail::JointGeometry&, bool,
                            JointRowsSlot&);

} // namespace frontier::core
