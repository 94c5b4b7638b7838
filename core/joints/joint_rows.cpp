// core/joints/joint_rows.cpp: dispatch by joint type and the row pieces the types share.
#include "core/joints/joint_rows.h"

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
void setAngularRow(JointRows& out, int row, const Vec3& g)
{
    out.J_a.row(row).setZero();
    out.J_b.row(row).setZero();
    out.J_a.block<1, 3>(row, 3) = -g.transpose();
    out.J_b.block<1, 3>(row, 3) = g.transpose();
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
int writeBallRows(const JointGeometry& g, JointRows& out, int row)
{
    if (!g.conditionsOnly)
    {
        out.J_a.block<3, 3>(row, 0) = -Mat3::Identity();
        out.J_a.block<3, 3>(row, 3) = skew(g.r_a);
        out.J_b.block<3, 3>(row, 0) = Mat3::Identity();
        out.J_b.block<3, 3>(row, 3) = -skew(g.r_b);
    }
    out.error.segment<3>(row) = g.p_b - g.p_a;
    return row + 3;
}

// Keeps the child's axis k_b on the parent's axis: C = [d_i . k_b, d_j . k_b] (docs/method.md §2
// in holonomic form). d/dt (d_i . k_b) = (w_b - w_a) . (k_b x d_i), exactly.
int writeAxisAlignmentRows(const Joint& joint, const JointGeometry& g, JointRows& out, int row)
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

// Child anchor stays on the parent's axis line: C = [d_i . (p_b - p_a), d_j . (p_b - p_a)]
// (docs/method.md §2). The exact derivative puts the lever arm of body a at p_b - x_a,
// the material point of a that coincides with p_b (docs/method.md §2).
int writeSlidingRows(const Joint& joint, const JointGeometry& g, JointRows& out, int row)
{
    const Vec3 gap = g.p_b - g.p_a;
    const Vec3 lever_a = g.p_b - g.x_a;
    for (const Vec3& local : {joint.perpParent1, joint.perpParent2})
    {
        const Vec3 d = g.R_a * local;
        out.J_a.row(row).setZero();
        out.J_b.row(row).setZero();
        out.J_a.block<1, 3>(row, 0) = -d.transpose();
        out.J_a.block<1, 3>(row, 3) = -lever_a.cross(d).transpose();
        out.J_b.block<1, 3>(row, 0) = d.transpose();
        out.J_b.block<1, 3>(row, 3) = g.r_b.cross(d).transpose();
        out.error(row) = d.dot(gap);
        ++row;
    }
    return row;
}

// No relative rotation: C = rotation vector of q_b (q_a q_rest)^-1, rows w_b - w_a
// (exact derivative at C = 0).
int writeWeldRotationRows(const Joint& joint, const JointPose& pose, JointRows& out, int row)
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
    out.error.segment<3>(row) = 2.0 * e.vec();
    return row + 3;
}

// Universal (Hooke) joint, docs/method.md §2, in holonomic form: a1 fixed in a, b2 fixed in b stay
// perpendicular, C = a1 . b2, d/dt C = (w_b - w_a) . (b2 x a1).
int writeTwistRow(const Joint& joint, const JointGeometry& g, JointRows& out, int row)
{
    const Vec3 a1 = g.R_a * joint.perpParent1;
    const Vec3 b2 = g.R_b * joint.angleChildAxis;
    setAngularRow(out, row, b2.cross(a1));
    out.error(row) = a1.dot(b2);
    return row + 1;
}

} // namespace detail

void evaluateJoint(const Joint& joint, const JointPose& pose, bool parentMoves, JointRows& out)
{
    evaluateJoint(joint, pose, detail::jointGeometry(joint, pose), parentMoves, out);
}

void evaluateJoint(const Joint& joint, const JointPose& pose, const detail::JointGeometry& g,
                   bool parentMoves, JointRows& out)
{
    using namespace detail;
    switch (joint.type)
    {
    case JointType::Ball:
    case JointType::Nail:
        writeBallJoint(joint, pose, g, out);
        break;
    case JointType::Revolute:
        writeRevoluteJoint(joint, pose, g, out);
        break;
    case JointType::Angle:
        writeAngleJoint(joint, pose, g, out);
        break;
    case JointType::Cylindrical:
        writeCylindricalJoint(joint, pose, g, out);
        break;
    case JointType::Prismatic:
        writePrismaticJoint(joint, pose, g, out);
        break;
    case JointType::Fixed:
        writeFixedJoint(joint, pose, g, out);
        break;
    }
    out.constraintRows = out.count;
    if (!parentMoves && !g.conditionsOnly)
    {
        out.J_a.setZero();
    }
}

} // namespace frontier::core
