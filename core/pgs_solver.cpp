// core/pgs_solver.cpp: projected Gauss-Seidel on the joint rows.
#include "core/pgs_solver.h"

namespace frontier::core
{

namespace
{
Vec6 applyInverseMass(const RowSystem& system, int body, const Vec6& f)
{
    Vec6 out;
    const std::size_t i = static_cast<std::size_t>(body);
    out.head<3>() = f.head<3>() / system.mass[i];
    out.tail<3>() = factoredInertia(system, i).ldlt().solve(f.tail<3>());
    return out;
}
} // namespace

void PgsSolver::factor(const RowSystem& system)
{
    mSystem = &system;
    const Model& model = *system.model;
    mRows.clear();
    for (std::size_t j = 0; j < model.joints.size(); ++j)
    {
        if (system.layout->jointBlock[j] < 0)
        {
            continue; // loop joints are not in the tree problem
        }
        const Joint& joint = model.joints[j];
        const JointRowsView rows = system.joints[j];
        const bool parentMoves = !jointToWorld(model, joint);
        for (int k = 0; k < rows.count; ++k)
        {
            Row row;
            row.joint = static_cast<int>(j);
            row.k = k;
            row.bodyA = parentMoves ? joint.parent : -1;
            row.bodyB = joint.child;
            row.JA = rows.J_a.row(k).transpose();
            row.JB = rows.J_b.row(k).transpose();
            row.WA = parentMoves ? applyInverseMass(system, joint.parent, row.JA) : Vec6::Zero();
            row.WB = applyInverseMass(system, joint.child, row.JB);
            row.compliance = k >= rows.constraintRows ? rows.compliance(k) : 0.0;
            const double diag = row.JA.dot(row.WA) + row.JB.dot(row.WB) + row.compliance;
            if (!(diag > 0.0))
            {
                throw SingularJointError(joint.name,
                                         "joint '" + joint.name + "': a row has no effective mass");
            }
            row.invDiag = 1.0 / diag;
            mRows.push_back(row);
        }
    }
}

void PgsSolver::solve(const BlockVector& rhs, BlockVector& solution)
{
    const RowSystem& system = *mSystem;
    const Model& model = *system.model;
    solution.resize(rhs.body.size(), rhs.joint.size());
    solution.setZero();
    // Unconstrained velocities u = M^-1 p.
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            solution.body[i] = applyInverseMass(system, static_cast<int>(i), rhs.body[i]);
        }
    }
    for (int sweep = 0; sweep < mIterations; ++sweep)
    {
        for (const Row& row : mRows)
        {
            Vec6& uB = solution.body[static_cast<std::size_t>(row.bodyB)];
            double jv = row.JB.dot(uB);
            if (row.bodyA >= 0)
            {
                jv += row.JA.dot(solution.body[static_cast<std::size_t>(row.bodyA)]);
            }
            double& lambda = solution.joint[static_cast<std::size_t>(row.joint)](row.k);
            const double delta =
                (rhs.joint[static_cast<std::size_t>(row.joint)](row.k) - jv - row.compliance * lambda) *
                row.invDiag;
            lambda += delta;
            uB += delta * row.WB;
            if (row.bodyA >= 0)
            {
                solution.body[static_cast<std::size_t>(row.bodyA)] += delta * row.WA;
            }
        }
    }
}

} // namespace frontier::core
