// core/extra_rows.cpp: contact, loop and limit rows (their solve: core/extra_rows_solve.cpp).
#include "core/extra_rows.h"

#include "core/collision_response.h"
#include "core/frontier_order.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

namespace frontier::core
{

namespace
{
struct LimitGeometry
{
    Vec3 axis_W;                          // the joint axis in world
    Eigen::Matrix<double, 1, 6> J_A, J_B; // d(coordinate)/dt = J_A u_A + J_B u_B
    double coordinate = 0.0;
};

LimitGeometry limitGeometry(const State& state, const Joint& joint)
{
    JointPose pose;
    if (joint.parent != cWorld)
    {
        pose.x_a = state.bodies[static_cast<std::size_t>(joint.parent)].position_W;
        pose.q_a = state.bodies[static_cast<std::size_t>(joint.parent)].orientation_WB;
    }
    pose.x_b = state.bodies[static_cast<std::size_t>(joint.child)].position_W;
    pose.q_b = state.bodies[static_cast<std::size_t>(joint.child)].orientation_WB;
    const detail::JointGeometry g = detail::jointGeometry(joint, pose);
    LimitGeometry out;
    const Vec3 k = g.R_a * joint.axisParent;
    out.axis_W = k;
    out.J_A.setZero();
    out.J_B.setZero();
    if (joint.type == JointType::Revolute)
    {
        // theta = atan2(i_c . d_j, i_c . d_i), i_c the child's copy of d_i; d theta/dt = (w_b - w_a) . k.
        const Vec3 ic = g.R_b * joint.perpChild1;
        out.coordinate = std::atan2(ic.dot(g.R_a * joint.perpParent2), ic.dot(g.R_a * joint.perpParent1));
        out.J_A.tail<3>() = -k.transpose();
        out.J_B.tail<3>() = k.transpose();
    }
    else
    {
        // s = k . (p_b - p_a); exact derivative with a's lever arm at p_b (PAPER.md §4 notes).
        out.coordinate = k.dot(g.p_b - g.p_a);
        out.J_A.head<3>() = -k.transpose();
        out.J_A.tail<3>() = -(g.p_b - g.x_a).cross(k).transpose();
        out.J_B.head<3>() = k.transpose();
        out.J_B.tail<3>() = g.r_b.cross(k).transpose();
    }
    return out;
}
} // namespace

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

double jointCoordinate(const Model& model, const State& state, int jointIndex)
{
    return limitGeometry(state, model.joints[static_cast<std::size_t>(jointIndex)]).coordinate;
}

void appendLimitBlocks(const Model& model, const State& state, int jointIndex, double margin,
                       std::vector<ExtraBlock>& out)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    if (!joint.limits || (joint.type != JointType::Revolute && joint.type != JointType::Prismatic))
    {
        return;
    }
    const LimitGeometry g = limitGeometry(state, joint);
    const double lower = (*joint.limits)[0];
    const double upper = (*joint.limits)[1];
    double sign = 0.0;
    double violation = 0.0;
    if (g.coordinate < lower + margin)
    {
        sign = 1.0; // keep the coordinate increasing
        violation = lower - g.coordinate;
    }
    else if (g.coordinate > upper - margin)
    {
        sign = -1.0;
        violation = g.coordinate - upper;
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
    block.J_A.row(0) = sign * g.J_A;
    block.J_B.row(0) = sign * g.J_B;
    if (block.bodyA < 0)
    {
        block.J_A.setZero();
    }
    block.error(0) = violation;
    block.source = jointIndex;
    out.push_back(block);
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
