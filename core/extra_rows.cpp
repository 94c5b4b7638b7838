// core/extra_rows.cpp: contact, limit and joint friction rows (their solve:
// core/extra_rows_solve.cpp; loop rows: core::buildLoopBlocks).
#include "core/extra_rows.h"

#include "core/contact_rows.h"
#include "core/frontier_order.h"
#include "core/joints/coordinates.h"
#include "core/joints/joint_types.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace frontier::core
{

ExtraBlock& appendContactBlock(const Model& model, const State& state, const Contact& contact,
                               double friction, int source, std::vector<ExtraBlock>& out)
{
    ExtraBlock& block = out.emplace_back(); // in place: a block is a few hundred bytes
    block.kind = ExtraBlock::Kind::Contact;
    block.count = friction > 0.0 ? 3 : 1; // no friction rows when friction is zero
    block.bodyA = contact.bodyA;
    block.bodyB = isMovingBody(model, contact.bodyB) ? contact.bodyB : -1;
    writeContactRows(model, state, contact.bodyA, contact.bodyB, contact.point_W, contact.normal_W,
                     block.count, block.J_A, block.J_B);
    block.error(0) = contact.depth;
    block.friction = friction;
    block.source = source;
    return block;
}

void appendLimitBlocks(const Model& model, const State& state, int jointIndex, double margin,
                       std::vector<ExtraBlock>& out)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const std::optional<JointCoordinate> limited = jointTypeInfo(joint.type).limitCoordinate;
    if (!joint.limits || !limited)
    {
        return;
    }
    // The angle continued from the last step (core/joints/coordinates.h): a limit beyond +-pi holds.
    const JointCoordinate coordinate = *limited;
    const double q = jointCoordinate(model, state, jointIndex, coordinate);
    const CoordinateRow row =
        coordinateRow(joint, detail::jointGeometry(joint, jointPose(state, joint)), coordinate);
    const double lower = (*joint.limits)[0];
    const double upper = (*joint.limits)[1];
    double sign = 0.0;
    double violation = 0.0;
    if (q < lower + margin)
    {
        sign = 1.0; // keep the coordinate increasing
        violation = lower - q;
    }
    else if (q > upper - margin)
    {
        sign = -1.0;
        violation = q - upper;
    }
    else
    {
        return;
    }
    ExtraBlock block;
    block.kind = ExtraBlock::Kind::Limit;
    block.count = 1;
    block.bodyA = jointToWorld(model, joint) ? -1 : joint.parent;
    block.bodyB = joint.child;
    block.J_A.row(0) = sign * row.J_a.transpose();
    block.J_B.row(0) = sign * row.J_b.transpose();
    if (block.bodyA < 0)
    {
        block.J_A.setZero();
    }
    block.error(0) = violation;
    block.source = jointIndex;
    out.push_back(block);
}

ExtraBlock& appendDriveBlock(const Model& model, const State& state, int jointIndex,
                             JointCoordinate coordinate, std::vector<ExtraBlock>& out)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const bool parentMoves = !jointToWorld(model, joint);
    const CoordinateRow row =
        coordinateRow(joint, detail::jointGeometry(joint, jointPose(state, joint)), coordinate);
    ExtraBlock& block = out.emplace_back();
    block.kind = ExtraBlock::Kind::Drive;
    block.count = 1;
    block.bodyA = parentMoves ? joint.parent : -1;
    block.bodyB = joint.child;
    if (parentMoves)
    {
        block.J_A.row(0) = row.J_a.transpose();
    }
    block.J_B.row(0) = row.J_b.transpose();
    block.source = jointIndex;
    return block;
}

void appendFrictionBlocks(const Model& model, const State& state, int jointIndex, double h,
                          std::vector<ExtraBlock>& out)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    if (!(joint.friction > 0.0))
    {
        return;
    }
    for (const JointCoordinate coordinate : jointCoordinates(joint.type))
    {
        // Target 0: the joint sticks unless the bound gives.
        appendDriveBlock(model, state, jointIndex, coordinate, out).bound = joint.friction * h;
    }
}

int layoutExtraRows(std::vector<ExtraBlock>& blocks)
{
    int offset = 0;
    for (ExtraBlock& block : blocks)
    {
        block.offset = offset;
        offset += block.count;
    }
    return offset;
}

} // namespace frontier::core
