// core/impulse_solver.cpp: assembling the rows, shared types, and the solver factory.
#include "core/impulse_solver.h"

#include "core/dense_solver.h"
#include "core/joints/coordinates.h"
#include "core/joints/drive.h"
#include "core/pgs_solver.h"
#include "core/tree_solver.h"

#include <numeric>

namespace frontier::core
{

void BlockVector::resize(std::size_t bodies, std::size_t joints)
{
    body.resize(bodies);
    joint.resize(joints);
}

void BlockVector::setZero()
{
    for (Vec6& v : body)
    {
        v.setZero();
    }
    for (Vec6& v : joint)
    {
        v.setZero();
    }
}

namespace
{
// R_WB of every body, once per assembly: the inertias and both ends of every joint read it.
void bodyRotations(const Model& model, const State& state, RowSystem& system)
{
    system.rotation_WB.resize(model.bodies.size());
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        system.rotation_WB[i] = state.bodies[i].orientation_WB.toRotationMatrix();
    }
}

// Joint k's geometry at `state` from the rotations bodyRotations left in `system`.
detail::JointGeometry jointGeometryAt(const Joint& joint, const JointPose& pose, const RowSystem& system)
{
    const Mat3 R_a = joint.parent == cWorld ? Mat3::Identity()
                                            : system.rotation_WB[static_cast<std::size_t>(joint.parent)];
    return detail::jointGeometry(joint, pose, R_a, system.rotation_WB[static_cast<std::size_t>(joint.child)]);
}

// The drive rows of joint k's block. A loop joint's actuators are extra rows (core/actuation.h):
// its drive rows damp only.
int jointDriveRows(const Model& model, const FrontierLayout& layout, std::size_t k)
{
    const int block = layout.jointBlock[k];
    return block >= 0 ? layout.blocks[static_cast<std::size_t>(block)].driveRows
                      : blockDriveRows(model.joints[k]);
}

template <class Rows>
void evaluateJointBlock(const Model& model, const FrontierLayout& layout, const JointPose& pose,
                        const detail::JointGeometry& g, int jointIndex, double driveStep,
                        std::span<const JointDriveGains> gains, Rows& out)
{
    const std::size_t k = static_cast<std::size_t>(jointIndex);
    const Joint& joint = model.joints[k];
    const bool parentMoves = !jointToWorld(model, joint);
    evaluateJoint(joint, pose, g, parentMoves, out);
    writeDriveRows(joint, jointDriveRows(model, layout, k), gains.empty() ? dampingGains(joint) : gains[k], g,
                   parentMoves, driveStep, out);
}

// Room in `table` for every joint's block (its conditions and drive rows), unless laid out for this
// layout already.
void layOutJointRows(const Model& model, const FrontierLayout* layout, JointRowsTable& table)
{
    if (layout != nullptr && table.laidOutFor(layout->id, model.joints.size()))
    {
        return;
    }
    std::vector<std::uint8_t> capacity(model.joints.size());
    std::vector<std::uint8_t> driveRows(model.joints.size());
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        driveRows[k] = static_cast<std::uint8_t>(layout != nullptr ? jointDriveRows(model, *layout, k) : 0);
        capacity[k] = static_cast<std::uint8_t>(jointRowCount(model.joints[k].type) + driveRows[k]);
    }
    table.layOut(capacity, driveRows, layout != nullptr ? layout->id : 0);
}
} // namespace

void assembleRows(const Model& model, const FrontierLayout& layout, const State& state, double driveStep,
                  RowSystem& system, std::span<const JointDriveGains> gains)
{
    system.model = &model;
    system.layout = &layout;
    const std::size_t nb = model.bodies.size();
    bodyRotations(model, state, system);
    system.mass.resize(nb);
    system.inertia_W.resize(nb);
    system.geometricInertia.clear();
    for (std::size_t i = 0; i < nb; ++i)
    {
        const Body& body = model.bodies[i];
        system.mass[i] = body.isStatic ? 0.0 : body.mass;
        system.inertia_W[i] = body.isStatic ? Mat3::Zero() : worldInertia(body, system.rotation_WB[i]);
    }
    layOutJointRows(model, &layout, system.joints);
    system.rowCount = 0;
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& joint = model.joints[k];
        const JointPose pose = jointPose(state, joint);
        JointRowsSlot rows = system.joints.slot(k);
        evaluateJointBlock(model, layout, pose, jointGeometryAt(joint, pose, system), static_cast<int>(k),
                           driveStep, gains, rows);
        system.joints.finish(k, rows);
        if (layout.jointBlock[k] >= 0)
        {
            system.rowCount += rows.count;
        }
    }
}

void assembleJointConditions(const Model& model, const State& state, RowSystem& system)
{
    bodyRotations(model, state, system);
    if (system.joints.size() != model.joints.size())
    {
        layOutJointRows(model, nullptr, system.joints); // room for the conditions alone
    }
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& joint = model.joints[k];
        const JointPose pose = jointPose(state, joint);
        detail::JointGeometry g = jointGeometryAt(joint, pose, system);
        g.conditionsOnly = true;
        JointRowsSlot rows = system.joints.slot(k);
        evaluateJoint(joint, pose, g, !jointToWorld(model, joint), rows);
        system.joints.finish(k, rows); // count = the conditions: the drive rows have no error
    }
}

void evaluateJointBlock(const Model& model, const FrontierLayout& layout, const State& state, int jointIndex,
                        double driveStep, std::span<const JointDriveGains> gains, JointRows& out)
{
    const Joint& joint = model.joints[static_cast<std::size_t>(jointIndex)];
    const JointPose pose = jointPose(state, joint);
    evaluateJointBlock(model, layout, pose, detail::jointGeometry(joint, pose), jointIndex, driveStep, gains,
                       out);
}

void extraRowVelocities(const std::vector<ExtraBlock>& blocks, const BlockVector& solution,
                        Eigen::VectorXd& out)
{
    int rows = 0;
    for (const ExtraBlock& block : blocks)
    {
        rows = std::max(rows, block.offset + block.count);
    }
    out.setZero(rows);
    for (const ExtraBlock& block : blocks)
    {
        // v += J_A u_A + J_B u_B, with fixed-size products for 3-row blocks (contacts with friction)
        auto add = [&](auto&& v, const auto& J_A, const auto& J_B)
        {
            if (block.bodyA >= 0)
            {
                v += J_A * solution.body[static_cast<std::size_t>(block.bodyA)];
            }
            if (block.bodyB >= 0)
            {
                v += J_B * solution.body[static_cast<std::size_t>(block.bodyB)];
            }
        };
        if (block.count == 3)
        {
            add(out.segment<3>(block.offset), block.J_A.topRows<3>(), block.J_B.topRows<3>());
        }
        else
        {
            add(out.segment(block.offset, block.count), block.J_A.topRows(block.count),
                block.J_B.topRows(block.count));
        }
    }
}

double freeDelassus(const RowSystem& system, std::size_t body, const Vec6& row)
{
    const Vec3 angular = row.tail<3>();
    return row.head<3>().squaredNorm() / system.mass[body] +
           angular.dot(system.inertia_W[body].ldlt().solve(angular));
}

void setFreeDelassus(const RowSystem& system, const std::vector<ExtraBlock>& blocks,
                     DelassusMatrix::Part& part)
{
    const std::vector<int>& treeOfBody = system.layout->treeOfBody;
    part.free.setZero(part.rows);
    for (std::size_t k = 0; k < part.blocks.size(); ++k)
    {
        const ExtraBlock& block = blocks[static_cast<std::size_t>(part.blocks[k])];
        for (int side = 0; side < 2; ++side)
        {
            const int body = side == 0 ? block.bodyA : block.bodyB;
            if (body < 0 || (part.tree >= 0 && treeOfBody[static_cast<std::size_t>(body)] != part.tree))
            {
                continue;
            }
            const Mat6& J = side == 0 ? block.J_A : block.J_B;
            for (int q = 0; q < block.count; ++q)
            {
                part.free(part.offsets[k] + q) +=
                    freeDelassus(system, static_cast<std::size_t>(body), J.row(q).transpose());
            }
        }
    }
}

// One solve per row of each part, with the row's impulse on the part's tree alone; the response
// (on that tree only: H is block diagonal by tree) read by the part's rows on the tree.
void ImpulseSolver::delassusParts(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G,
                                  std::span<const int> parts)
{
    const std::vector<int>& treeOfBody = mSystem->layout->treeOfBody;
    BlockVector impulse, response;
    impulse.resize(mSystem->model->bodies.size(), mSystem->model->joints.size());
    response.resize(mSystem->model->bodies.size(), mSystem->model->joints.size());
    for (int p : parts)
    {
        DelassusMatrix::Part& part = G.part(p);
        setFreeDelassus(*mSystem, blocks, part);
        auto onTree = [&](int body)
        { return body >= 0 && (part.tree < 0 || treeOfBody[static_cast<std::size_t>(body)] == part.tree); };
        for (std::size_t k = 0; k < part.blocks.size(); ++k)
        {
            const ExtraBlock& block = blocks[static_cast<std::size_t>(part.blocks[k])];
            for (int q = 0; q < block.count; ++q)
            {
                impulse.setZero();
                for (int side = 0; side < 2; ++side)
                {
                    const int body = side == 0 ? block.bodyA : block.bodyB;
                    if (onTree(body))
                    {
                        impulse.body[static_cast<std::size_t>(body)] +=
                            (side == 0 ? block.J_A : block.J_B).row(q).transpose();
                    }
                }
                solve(impulse, response);
                for (std::size_t k2 = 0; k2 < part.blocks.size(); ++k2)
                {
                    const ExtraBlock& other = blocks[static_cast<std::size_t>(part.blocks[k2])];
                    for (int q2 = 0; q2 < other.count; ++q2)
                    {
                        double v = 0.0;
                        for (int side = 0; side < 2; ++side)
                        {
                            const int body = side == 0 ? other.bodyA : other.bodyB;
                            if (onTree(body))
                            {
                                v += (side == 0 ? other.J_A : other.J_B)
                                         .row(q2)
                                         .dot(response.body[static_cast<std::size_t>(body)]);
                            }
                        }
                        part.G(part.offsets[k2] + q2, part.offsets[k] + q) = v;
                    }
                }
            }
        }
    }
    G.touch();
}

void ImpulseSolver::delassus(const std::vector<ExtraBlock>& blocks, DelassusMatrix& G)
{
    G.layOut(blocks, mSystem->layout->treeOfBody);
    mAllParts.resize(static_cast<std::size_t>(G.parts()));
    std::iota(mAllParts.begin(), mAllParts.end(), 0);
    delassusParts(blocks, G, mAllParts);
}

void ImpulseSolver::delassus(const std::vector<ExtraBlock>& blocks, int rows, Eigen::MatrixXd& G)
{
    delassus(blocks, mDenseScratch);
    mDenseScratch.toDense(G, rows);
}

void ImpulseSolver::addExtraImpulses(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda,
                                     BlockVector& rhs)
{
    for (const ExtraBlock& block : blocks)
    {
        // J_A^T l on A, J_B^T l on B, with fixed-size products for 3-row blocks (contacts with friction)
        auto add = [&](const auto& l, const auto& J_A, const auto& J_B)
        {
            if (block.bodyA >= 0)
            {
                rhs.body[static_cast<std::size_t>(block.bodyA)] += J_A.transpose() * l;
            }
            if (block.bodyB >= 0)
            {
                rhs.body[static_cast<std::size_t>(block.bodyB)] += J_B.transpose() * l;
            }
        };
        if (block.count == 3)
        {
            const Eigen::Vector3d l = lambda.segment<3>(block.offset);
            add(l, block.J_A.topRows<3>(), block.J_B.topRows<3>());
        }
        else
        {
            add(lambda.segment(block.offset, block.count), block.J_A.topRows(block.count),
                block.J_B.topRows(block.count));
        }
    }
}

void ImpulseSolver::applyExtraImpulses(const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda,
                                       BlockVector& solution)
{
    mExtraRhs.resize(solution.body.size(), solution.joint.size());
    mExtraRhs.setZero();
    addExtraImpulses(blocks, lambda, mExtraRhs);
    solve(mExtraRhs, mExtraResponse);
    for (std::size_t i = 0; i < solution.body.size(); ++i)
    {
        solution.body[i] += mExtraResponse.body[i];
    }
    for (std::size_t j = 0; j < solution.joint.size(); ++j)
    {
        solution.joint[j] += mExtraResponse.joint[j];
    }
}

std::unique_ptr<ImpulseSolver> makeSolver(SolverKind kind, int pgsIterations)
{
    switch (kind)
    {
    case SolverKind::Linear:
        return std::make_unique<TreeSolver>();
    case SolverKind::Dense:
        return std::make_unique<DenseSolver>();
    case SolverKind::Pgs:
        return std::make_unique<PgsSolver>(pgsIterations);
    }
    return nullptr;
}

} // namespace frontier::core
