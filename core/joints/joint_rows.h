// core/joints/joint_rows.h: a joint as rows of a Jacobian between two bodies (docs/method.md §2).
//
// Every joint k between body a (the joint's parent, possibly the world) and body b (its child)
// is r_k scalar velocity conditions
//     J_a u_a + J_b u_b = 0,        u = [v; w] (world frame: m/s, rad/s)
// and the joint impulse body a receives is J_a^T lambda, body b J_b^T lambda (N s, N m s).
// Each row is the exact time derivative of a position-level condition C(q) = 0, so the same
// rows drive the velocity solve and the drift correction; `error` holds C (m or rad).
// A joint's block may end with drive rows (core/joints/drive.h): compliant rows on its
// coordinates, J u + E lambda = c, with no position condition (error 0).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

namespace frontier::core
{

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
// A joint's Jacobian blocks are stored row by row, so a joint of r rows occupies its first r x 6
// doubles contiguously: the O(n) factorization streams only the rows a joint has.
using JacobianRows = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;

struct JointRows
{
    int count = 0;          // rows of the joint's block, 3..6: its conditions, then its drive rows
    int constraintRows = 0; // rows 0..constraintRows-1 are the conditions C(q) = 0 (docs/method.md §2)
    int positionRows = 0;   // rows 0..positionRows-1 are positions (m), the rest angles (rad)
    JacobianRows J_a = JacobianRows::Zero(); // rows 0..count-1 used; zero for a world parent
    JacobianRows J_b = JacobianRows::Zero();
    Vec6 error = Vec6::Zero(); // C(q): position-level violation of each row (m or rad); 0 for drive rows
    // Drive rows (constraintRows..count-1): compliance E of J u + E lambda = c, (m/s)/(N s) or
    // (rad/s)/(N m s); entries of constraint rows are not read.
    Vec6 compliance = Vec6::Zero();
};

// Pose of the two bodies of a joint. For a world parent, the parent pose is the identity; for a
// static parent, that body's fixed pose.
struct JointPose
{
    Vec3 x_a = Vec3::Zero(); // centre of mass of a (m)
    Quat q_a = Quat::Identity();
    Vec3 x_b = Vec3::Zero();
    Quat q_b = Quat::Identity();
};

// Fills the condition rows for the joint's type at the given pose (count = constraintRows; drive
// rows are appended by writeDriveRows, core/joints/drive.h). parentMoves: false for world/static
// parents (J_a is then left zero).
void evaluateJoint(const Joint& joint, const JointPose& pose, bool parentMoves, JointRows& out);

namespace detail
{
// Geometry shared by the per-type files, evaluated once per joint.
struct JointGeometry
{
    Mat3 R_a, R_b;
    Vec3 p_a, p_b; // anchors in world (m)
    Vec3 r_a, r_b; // p - x: lever arms from the centres of mass (m)
    Vec3 x_a;      // centre of mass of a (m)
    // Only C(q) is wanted (assembleJointConditions): writers may leave J_a and J_b as they were.
    bool conditionsOnly = false;
};
JointGeometry jointGeometry(const Joint& joint, const JointPose& pose);
// The same with the bodies' rotation matrices given (R_a: identity for a world parent), as
// pose.q_a.toRotationMatrix() and pose.q_b.toRotationMatrix() would give them.
JointGeometry jointGeometry(const Joint& joint, const JointPose& pose, const Mat3& R_a, const Mat3& R_b);

// Row writers, each appending at row `row` and returning the next free row.
int writeBallRows(const JointGeometry& g, JointRows& out, int row);
int writeAxisAlignmentRows(const Joint& joint, const JointGeometry& g, JointRows& out, int row);
int writeSlidingRows(const Joint& joint, const JointGeometry& g, JointRows& out, int row);
int writeWeldRotationRows(const Joint& joint, const JointPose& pose, JointRows& out, int row);
int writeTwistRow(const Joint& joint, const JointGeometry& g, JointRows& out, int row);

// Per type; g = jointGeometry(joint, pose).
void writeBallJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
void writeRevoluteJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
void writeAngleJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
void writeCylindricalJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
void writePrismaticJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
void writeFixedJoint(const Joint& joint, const JointPose& pose, const JointGeometry& g, JointRows& out);
} // namespace detail

// evaluateJoint with the joint's geometry at that pose at hand (detail::jointGeometry), which the
// drive rows reuse.
void evaluateJoint(const Joint& joint, const JointPose& pose, const detail::JointGeometry& g,
                   bool parentMoves, JointRows& out);

} // namespace frontier::core
