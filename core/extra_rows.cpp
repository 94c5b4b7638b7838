// core/extra_rows.cpp: contact, loop and limit rows, and their block Gauss-Seidel solve.
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

ExtraBlock makeContactBlock(const Model& model, const State& state, const Contact& contact, double friction,
                            int source)
{
    const ContactRows rows =
        contactRows(model, state, contact.bodyA, contact.bodyB, contact.point_W, contact.normal_W);
    ExtraBlock block;
    block.kind = ExtraBlock::Kind::Contact;
    block.count = friction > 0.0 ? 3 : 1; // no friction rows when friction is zero
    block.bodyA = contact.bodyA;
    block.bodyB = isMovingBody(model, contact.bodyB) ? contact.bodyB : -1;
    block.J_A.topRows(block.count) = rows.J_A.topRows(block.count);
    block.J_B.topRows(block.count) = rows.J_B.topRows(block.count);
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

ExtraSolveStats solveExtraRows(const std::vector<ExtraBlock>& blocks, const Eigen::MatrixXd& G,
                               const Eigen::VectorXd& freeVelocity, const ExtraSolveSettings& settings,
                               Eigen::VectorXd& lambda, ExtraSolveScratch& scratch)
{
    ExtraSolveStats stats;
    const Eigen::Index m = G.rows();
    if (m == 0)
    {
        return stats;
    }
    // A row that can barely move (a point pinned by joints) has a tiny pivot: regularize it by a
    // relative 1e-9 of the largest diagonal so the update stays bounded.
    const double regularization = 1e-9 * G.diagonal().cwiseAbs().maxCoeff() + 1e-300;
    // Inverse pivots, once: loops by their whole block, contacts normal row alone and the 2x2
    // tangential block, limits their one row.
    std::vector<Mat6>& inverse = scratch.inverse;
    inverse.assign(blocks.size(), Mat6::Zero());
    for (std::size_t b = 0; b < blocks.size(); ++b)
    {
        const int o = blocks[b].offset;
        const int n = blocks[b].count;
        if (blocks[b].kind == ExtraBlock::Kind::Loop)
        {
            const Eigen::MatrixXd block =
                G.block(o, o, n, n) + regularization * Eigen::MatrixXd::Identity(n, n);
            inverse[b].topLeftCorner(n, n) = block.inverse();
            continue;
        }
        inverse[b](0, 0) = 1.0 / (G(o, o) + regularization);
        if (n == 3)
        {
            const Eigen::Matrix2d tt =
                G.block<2, 2>(o + 1, o + 1) + regularization * Eigen::Matrix2d::Identity();
            inverse[b].block<2, 2>(1, 1) = tt.inverse();
        }
    }
    Eigen::VectorXd& velocity = scratch.velocity;
    velocity.noalias() = freeVelocity;
    velocity.noalias() += G * lambda; // J u with the current impulses
    using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
    for (int sweep = 0; sweep < settings.maxSweeps; ++sweep)
    {
        double change = 0.0;
        double largest = 0.0;
        for (std::size_t b = 0; b < blocks.size(); ++b)
        {
            const ExtraBlock& block = blocks[b];
            const int o = block.offset;
            const int n = block.count;
            const SmallVec old = lambda.segment(o, n);
            SmallVec next = old;
            if (block.kind == ExtraBlock::Kind::Loop)
            {
                const SmallVec target = block.target.head(n);
                next += inverse[b].topLeftCorner(n, n) * (target - velocity.segment(o, n));
            }
            else
            {
                // Normal (or limit) row: one-sided.
                next(0) = std::max(0.0, old(0) + inverse[b](0, 0) * (block.target(0) - velocity(o)));
                if (n == 3)
                {
                    // Tangential rows after the normal change, then the friction cone
                    // |lambda_t| <= mu lambda_n by radial projection.
                    const Eigen::Vector2d vt =
                        velocity.segment<2>(o + 1) + G.block<2, 1>(o + 1, o) * (next(0) - old(0));
                    Eigen::Vector2d lt = old.segment<2>(1) - inverse[b].block<2, 2>(1, 1) * vt;
                    const double limit = block.friction * next(0);
                    const double tangential = lt.norm();
                    if (tangential > limit)
                    {
                        // Sliding: the anisotropic 2x2 step would leave the friction off the
                        // slip direction at the fixed point; an isotropic step (k = 2 / trace)
                        // followed by the radial projection converges to friction opposing the slip.
                        const double k = 2.0 / (G(o + 1, o + 1) + G(o + 2, o + 2) + 2.0 * regularization);
                        lt = old.segment<2>(1) - k * vt;
                        const double slide = lt.norm();
                        if (slide > limit)
                        {
                            lt *= slide > 0.0 ? limit / slide : 0.0;
                        }
                    }
                    next.segment<2>(1) = lt;
                }
            }
            const SmallVec delta = next - old;
            const double step = delta.cwiseAbs().maxCoeff();
            if (step > 0.0)
            {
                lambda.segment(o, n) = next;
                velocity.noalias() += G.middleCols(o, n) * delta;
            }
            change = std::max(change, step);
            largest = std::max(largest, next.cwiseAbs().maxCoeff());
        }
        stats.sweeps = sweep + 1;
        stats.lastChange = largest > 0.0 ? change / largest : 0.0;
        if (change <= settings.tolerance * largest || change < 1e-14)
        {
            break;
        }
    }
    return stats;
}

} // namespace frontier::core
