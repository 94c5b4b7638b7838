// core/step_report.cpp: what the last step passed through its joints and contacts, read when asked
// (the `--joints` and `--contacts` outputs). Nothing here runs inside step() but for rattle4, whose
// first two stages' impulses are added up at their end (addRowImpulses): a step keeps its
// impulses anyway (the joints' in the step context's solution, the extra rows' in the contact problem, the
// rattle projection's in RattleProjection::impulses, the loops' drift correction in
// DriftCorrection::loopCorrection).
//
// A joint's impulse on its child is J_b^T lambda summed over the rows of the joint: its block in
// the tree (conditions and drive rows), and its extra rows (loop, limit, friction). Those rows
// were applied at several poses within the step (its start; rattle's end; the drift correction's
// iterates); here all are taken at the pose of the state the step produced. The impulse a row
// passes is kept exactly, and the split into force and torque is that of one pose, so a ball
// joint passes no torque about its anchor and a hinge none about its axis (but through its limit
// or drive rows), to round-off.
#include "core/frontier_order.h"
#include "core/joints/coordinates.h"
#include "core/step/step_stages.h"

#include <cmath>

namespace frontier::core
{

namespace
{
// A one-row block of a joint (a limit, joint friction) acts along one of the joint's coordinates,
// evaluated when the block was built: the same coordinate's child row at the pose of `g`, with the
// block's sign (the coordinate rows of one joint are orthogonal, so the nearest is that one).
Vec6 coordinateRowLike(const Joint& joint, const detail::JointGeometry& g, const Vec6& rowThen)
{
    Vec6 best = rowThen;
    double bestCosine = 0.0;
    for (const JointCoordinate coordinate : jointCoordinates(joint.type))
    {
        const Vec6 row = coordinateRow(joint, g, coordinate).J_b;
        const double cosine = row.dot(rowThen) / (row.norm() * rowThen.norm());
        if (std::abs(cosine) > std::abs(bestCosine))
        {
            bestCosine = cosine;
            best = cosine < 0.0 ? Vec6(-row) : row;
        }
    }
    return best;
}
} // namespace

void StepStages::jointChildImpulses(const State& state, std::vector<Vec6>& out) const
{
    out.assign(mModel.joints.size(), Vec6::Zero());
    addRowImpulses(state, out);
    // Effort actuators pass their commanded (clipped) impulse through the joint as applied forces.
    const std::span<const ActuatorEffort> efforts = mActuation.efforts();
    for (std::size_t a = 0; a < mModel.actuators.size() && a < efforts.size(); ++a)
    {
        const Actuator& actuator = mModel.actuators[a];
        if (actuator.kind != ActuatorKind::Effort)
        {
            continue;
        }
        const Joint& joint = mModel.joints[static_cast<std::size_t>(actuator.joint)];
        const detail::JointGeometry g = detail::jointGeometry(joint, jointPose(state, joint));
        out[static_cast<std::size_t>(actuator.joint)] +=
            coordinateRow(joint, g, actuator.coordinate).J_b * (efforts[a].effort * mStep.dt);
    }
    // About the anchor: the torque about the child's centre of mass less r_b x F.
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        const Joint& joint = mModel.joints[k];
        const Vec3 r_b = detail::jointGeometry(joint, jointPose(state, joint)).r_b;
        out[k].tail<3>() -= r_b.cross(Vec3(out[k].head<3>()));
    }
}

// The impulses of the rows of the last step's solves (rattle4: of its three stages) on each joint's
// child, linear and angular about its centre of mass, added into out.
void StepStages::addRowImpulses(const State& state, std::vector<Vec6>& out) const
{
    JointRows rows;
    // A whole joint block (a tree joint's, a loop's): lambda row by row as in JointRows.
    auto addBlock = [&](int k, const auto& lambda)
    {
        evaluateJointBlock(mModel, mLayout, state, k, mStep.driveStep, mActuation.gains(), rows);
        out[static_cast<std::size_t>(k)] +=
            rows.J_b.topRows(rows.count).transpose() * lambda.head(rows.count);
    };
    auto addExtra = [&](const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda)
    {
        for (const ExtraBlock& block : blocks)
        {
            if (block.kind == ExtraBlock::Kind::Contact || lambda.size() < block.offset + block.count)
            {
                continue;
            }
            if (block.kind == ExtraBlock::Kind::Loop)
            {
                addBlock(block.source, lambda.segment(block.offset, block.count));
                continue;
            }
            const Joint& joint = mModel.joints[static_cast<std::size_t>(block.source)];
            const detail::JointGeometry g = detail::jointGeometry(joint, jointPose(state, joint));
            for (int r = 0; r < block.count; ++r)
            {
                out[static_cast<std::size_t>(block.source)] +=
                    coordinateRowLike(joint, g, block.J_B.row(r).transpose()) * lambda(block.offset + r);
            }
        }
    };
    for (std::size_t k = 0; k < mModel.joints.size(); ++k)
    {
        if (mLayout.jointBlock[k] >= 0)
        {
            addBlock(static_cast<int>(k), mComposedStep ? Vec6(mStep.solution.joint[k] + mStageJoint[k])
                                                        : Vec6(mStep.solution.joint[k]));
        }
    }
    addExtra(mProblem.blocks(), mProblem.impulses());
    addExtra(mStep.loopBlocks, mDrift.loopCorrection());
    if (mStep.rattle())
    {
        addExtra(mRattle.blocks(), mRattle.impulses()); // the velocity projection at the end of a rattle step
    }
    if (mComposedStep)
    {
        for (const auto& [blocks, lambda] : mStageExtras) // rattle4: the first two stages' extra rows
        {
            addExtra(blocks, lambda);
        }
    }
}

void StepStages::contactImpulses(std::vector<ContactImpulse>& out) const
{
    out.clear();
    for (const Contact& contact : mProblem.contacts())
    {
        out.push_back({contact, Vec3::Zero()});
    }
    // Body A receives J_A^T lambda; its linear part is minus what B receives (a contact's rows
    // conserve momentum), and B may be static, with no rows of its own.
    auto add = [&](const std::vector<ExtraBlock>& blocks, const Eigen::VectorXd& lambda)
    {
        for (const ExtraBlock& block : blocks)
        {
            if (block.kind == ExtraBlock::Kind::Contact && lambda.size() >= block.offset + block.count)
            {
                const Vec6 onA =
                    block.J_A.topRows(block.count).transpose() * lambda.segment(block.offset, block.count);
                out[static_cast<std::size_t>(block.source)].impulse_W -= onA.head<3>();
            }
        }
    };
    add(mProblem.blocks(), mProblem.impulses());
    if (mStep.rattle())
    {
        add(mRattle.blocks(), mRattle.impulses());
    }
}

int StepStages::pushingLimitRows() const
{
    int count = 0;
    for (const ExtraBlock& block : mProblem.blocks())
    {
        if (block.kind == ExtraBlock::Kind::Limit && block.offset < mProblem.impulses().size() &&
            mProblem.impulses()(block.offset) > 0.0)
        {
            ++count;
        }
    }
    return count;
}

} // namespace frontier::core
