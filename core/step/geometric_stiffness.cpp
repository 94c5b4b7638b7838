// core/step/geometric_stiffness.cpp: the geometric stiffness of joints under large forces
// (docs/method.md §7a, eq. (11c)).
#include "core/step/geometric_stiffness.h"

#include <algorithm>

namespace frontier::core
{

void measureJointLoads(const Model& model, const RowSystem& rows, const BlockVector& solution,
                       std::vector<double>& loads)
{
    loads.resize(2 * model.joints.size(), 0.0);
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        const Joint& joint = model.joints[k];
        const JointRowsTable::Rows r = rows.joints.rows(k);
        const int n = r.constraintRows;
        Vec3 onChild = Vec3::Zero(); // N s: J_b^T lambda, linear part, row by row (no dynamic-size product)
        for (int row = 0; row < n; ++row)
        {
            onChild += Eigen::Map<const Vec3>(r.J_b + 6 * row) * solution.joint[k](row);
        }
        const Vec3 leverChild = rows.rotation_WB[static_cast<std::size_t>(joint.child)] * joint.anchorChild;
        double parentEnd = 0.0;
        if (joint.parent >= 0 && !model.bodies[static_cast<std::size_t>(joint.parent)].isStatic)
        {
            const Vec3 leverParent =
                rows.rotation_WB[static_cast<std::size_t>(joint.parent)] * joint.anchorParent;
            parentEnd = std::max(0.0, -onChild.dot(leverParent));
        }
        const double childEnd = std::max(0.0, onChild.dot(leverChild));
        loads[2 * k] = std::max(parentEnd, cLoadDecay * loads[2 * k]);
        loads[2 * k + 1] = std::max(childEnd, cLoadDecay * loads[2 * k + 1]);
    }
}

void geometricInertias(const Model& model, const std::vector<double>& loads, double dt,
                       LargeVector<double>& out)
{
    // eq. (11c): h^2 k_i = h sum over body i's joint ends of Λ . ρ (kg m^2).
    out.assign(model.bodies.size(), 0.0);
    if (loads.size() != 2 * model.joints.size())
    {
        return;
    }
    const auto add = [&](int body, double load)
    {
        if (body >= 0 && !model.bodies[static_cast<std::size_t>(body)].isStatic)
        {
            out[static_cast<std::size_t>(body)] += dt * load;
        }
    };
    for (std::size_t k = 0; k < model.joints.size(); ++k)
    {
        add(model.joints[k].parent, loads[2 * k]);
        add(model.joints[k].child, loads[2 * k + 1]);
    }
}

int stiffenLoadedBodies(const Model& model, const std::vector<double>& loads, double dt, RowSystem& rows)
{
    rows.geometricInertia.clear();
    if (loads.size() != 2 * model.joints.size())
    {
        return 0;
    }
    geometricInertias(model, loads, dt, rows.geometricInertia);
    int stiffened = 0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        const double meanMoment = rows.inertia_W[i].trace() / 3.0; // kg m^2
        if (rows.geometricInertia[i] > cStiffRatio * meanMoment)
        {
            ++stiffened;
        }
        else
        {
            rows.geometricInertia[i] = 0.0;
        }
    }
    if (stiffened == 0)
    {
        rows.geometricInertia.clear();
    }
    return stiffened;
}

} // namespace frontier::core
