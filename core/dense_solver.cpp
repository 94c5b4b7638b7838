// core/dense_solver.cpp: Moore's dense Gaussian elimination of the impulse system.
#include "core/dense_solver.h"

#include <cmath>

namespace frontier::core
{

Eigen::MatrixXd DenseSolver::assemble(const RowSystem& system)
{
    const Model& model = *system.model;
    const FrontierLayout& layout = *system.layout;
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(layout.size, layout.size);
    for (const LayoutBlock& block : layout.blocks)
    {
        if (block.kind == LayoutBlock::Kind::Node)
        {
            const std::size_t i = static_cast<std::size_t>(block.index);
            a.block<3, 3>(block.offset, block.offset) = system.mass[i] * Mat3::Identity();
            a.block<3, 3>(block.offset + 3, block.offset + 3) = factoredInertia(system, i);
            continue;
        }
        const Joint& joint = model.joints[static_cast<std::size_t>(block.index)];
        const JointRows& rows = system.joints[static_cast<std::size_t>(block.index)];
        const int r = block.dim;
        auto couple = [&](int body, const JacobianRows& J)
        {
            if (body == cWorld || model.bodies[static_cast<std::size_t>(body)].isStatic)
            {
                return;
            }
            const int col =
                layout.blocks[static_cast<std::size_t>(layout.bodyBlock[static_cast<std::size_t>(body)])]
                    .offset;
            a.block(block.offset, col, r, 6) = J.topRows(r);
            a.block(col, block.offset, 6, r) = J.topRows(r).transpose();
        };
        couple(joint.parent, rows.J_a);
        couple(joint.child, rows.J_b);
        // Drive rows J u + E lambda = c: -E on the diagonal (the unknown is -lambda).
        for (int q = r - block.driveRows; q < r; ++q)
        {
            a(block.offset + q, block.offset + q) = -rows.compliance(q);
        }
    }
    return a;
}

void DenseSolver::factor(const RowSystem& system)
{
    mSystem = &system;
    const FrontierLayout& layout = *system.layout;
    mLu.compute(assemble(system));
    // Gaussian elimination meets a (near) zero pivot when rows are dependent: name the unknown.
    const Eigen::MatrixXd& lu = mLu.matrixLU();
    const double scale = lu.diagonal().cwiseAbs().maxCoeff();
    for (int i = 0; i < lu.rows(); ++i)
    {
        if (!(std::abs(lu(i, i)) > 1e-13 * scale))
        {
            for (const LayoutBlock& block : layout.blocks)
            {
                if (i >= block.offset && i < block.offset + block.dim)
                {
                    const bool edge = block.kind == LayoutBlock::Kind::Edge;
                    const std::string& name =
                        edge ? system.model->joints[static_cast<std::size_t>(block.index)].name
                             : system.model->bodies[static_cast<std::size_t>(block.index)].name;
                    throw SingularJointError(name,
                                             std::string(edge ? "joint '" : "body '") + name +
                                                 "': the dense impulse system is singular (dependent rows)");
                }
            }
        }
    }
}

void DenseSolver::solve(const BlockVector& rhs, BlockVector& solution)
{
    const FrontierLayout& layout = *mSystem->layout;
    mRhs.resize(layout.size);
    for (const LayoutBlock& block : layout.blocks)
    {
        const Vec6& src = block.kind == LayoutBlock::Kind::Node
                              ? rhs.body[static_cast<std::size_t>(block.index)]
                              : rhs.joint[static_cast<std::size_t>(block.index)];
        mRhs.segment(block.offset, block.dim) = src.head(block.dim);
    }
    const Eigen::VectorXd x = mLu.solve(mRhs);
    solution.resize(rhs.body.size(), rhs.joint.size());
    solution.setZero();
    for (const LayoutBlock& block : layout.blocks)
    {
        if (block.kind == LayoutBlock::Kind::Node)
        {
            solution.body[static_cast<std::size_t>(block.index)] = x.segment<6>(block.offset);
        }
        else
        {
            solution.joint[static_cast<std::size_t>(block.index)].head(block.dim) =
                -x.segment(block.offset, block.dim);
        }
    }
}

} // namespace frontier::core
