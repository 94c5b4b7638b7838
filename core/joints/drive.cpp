// core/joints/drive.cpp: the compliant drive rows of a joint's block (viscous damping).
#include "core/joints/drive.h"

#include "core/joints/coordinates.h"

#include <cmath>

namespace frontier::core
{

int blockDriveRows(const Joint& joint)
{
    return joint.damping > 0.0 ? static_cast<int>(jointCoordinates(joint.type).size()) : 0;
}

int jointBlockRows(const Joint& joint)
{
    return jointRowCount(joint.type) + blockDriveRows(joint);
}

void writeDriveRows(const Joint& joint, const detail::JointGeometry& g, bool parentMoves, double h,
                    JointRows& out)
{
    if (blockDriveRows(joint) == 0)
    {
        return;
    }
    // Implicit damping: E = 1 / (d h). With no time (or a product that underflows) the row's
    // limit as E grows: J = 0, E = 1, lambda = 0.
    const double compliance = 1.0 / (joint.damping * h);
    const bool active = std::isfinite(compliance);
    for (const JointCoordinate coordinate : jointCoordinates(joint.type))
    {
        const int row = out.count++;
        out.J_a.row(row).setZero();
        out.J_b.row(row).setZero();
        if (active)
        {
            const CoordinateRow J = coordinateRow(joint, g, coordinate);
            if (parentMoves)
            {
                out.J_a.row(row) = J.J_a.transpose();
            }
            out.J_b.row(row) = J.J_b.transpose();
        }
        out.compliance(row) = active ? compliance : 1.0;
        out.error(row) = 0.0;
    }
}

} // namespace frontier::core
