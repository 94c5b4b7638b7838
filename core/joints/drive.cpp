// core/joints/drive.cpp: the compliant drive rows of a joint's block (damping, servos, motors).
#include "core/joints/drive.h"

#include "core/joints/coordinates.h"

#include <cmath>

namespace frontier::core
{

DriveRow driveRow(const DriveGains& gains, double h, double force, double rigidSpeed)
{
    if (gains.rigid && h > 0.0)
    {
        return {0.0, rigidSpeed, true};
    }
    // E = 1 / (h (h k + d)); with no time (or a product that underflows) the row's limit as E
    // grows: inactive.
    const double spring = h * gains.stiffness + gains.damping; // h k + d
    const double compliance = 1.0 / (h * spring);
    const bool active = std::isfinite(compliance);
    return {active ? compliance : 1.0, active ? force / spring : 0.0, active};
}

JointDriveGains dampingGains(const Joint& joint)
{
    JointDriveGains gains;
    for (DriveGains& g : gains)
    {
        g.damping = joint.damping;
    }
    return gains;
}

std::vector<std::uint8_t> actuatedJoints(const Model& model)
{
    std::vector<std::uint8_t> actuated(model.joints.size(), 0);
    for (const Actuator& actuator : model.actuators)
    {
        if (actuator.kind != ActuatorKind::Effort)
        {
            actuated[static_cast<std::size_t>(actuator.joint)] = 1;
        }
    }
    return actuated;
}

int blockDriveRows(const Joint& joint, bool actuated)
{
    return joint.damping > 0.0 || actuated ? static_cast<int>(jointCoordinates(joint.type).size()) : 0;
}

int jointBlockRows(const Joint& joint, bool actuated)
{
    return jointRowCount(joint.type) + blockDriveRows(joint, actuated);
}

template <class Rows>
void writeDriveRows(const Joint& joint, int driveRows, const JointDriveGains& gains,
                    const detail::JointGeometry& g, bool parentMoves, double h, Rows& out)
{
    if (driveRows == 0)
    {
        return;
    }
    const std::span<const JointCoordinate> coordinates = jointCoordinates(joint.type);
    for (std::size_t k = 0; k < coordinates.size(); ++k)
    {
        const DriveRow drive = driveRow(gains[k], h, 0.0);
        const int row = out.count++;
        out.J_a.row(row).setZero();
        out.J_b.row(row).setZero();
        if (drive.active)
        {
            const CoordinateRow J = coordinateRow(joint, g, coordinates[k]);
            if (parentMoves)
            {
                out.J_a.row(row) = J.J_a.transpose();
            }
            out.J_b.row(row) = J.J_b.transpose();
        }
        out.compliance(row) = drive.compliance;
        out.error(row) = 0.0;
    }
}

template void writeDriveRows(const Joint&, int, const JointDriveGains&, const detail::JointGeometry&, bool,
                             double, JointRows&);
template void writeDriveRows(const Joint&, int, const JointDriveGains&, const detail::JointGeometry&, bool,
                             double, JointRowsSlot&);

} // namespace frontier::core
