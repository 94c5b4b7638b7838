// core/penetration.cpp: the bounds of the penetration projection (see core/penetration.h).
#include "core/penetration.h"

#include <algorithm>

namespace frontier::core
{

namespace
{
// The sum of part(i, J_i) over the block's moving bodies i, J_i the body's part of the first row.
template <class Part> double sumOverBodies(const ExtraBlock& block, Part part)
{
    double sum = 0.0;
    if (block.bodyA >= 0)
    {
        sum += part(static_cast<std::size_t>(block.bodyA), block.J_A.row(0).transpose());
    }
    if (block.bodyB >= 0)
    {
        sum += part(static_cast<std::size_t>(block.bodyB), block.J_B.row(0).transpose());
    }
    return sum;
}
} // namespace

bool heldByJoints(const ExtraBlock& block, double delassus, const RowSystem& rows,
                  const std::vector<PrincipalAxes>& principal, double ratio)
{
    // J M^-1 J^T = sum |J_v|^2 / m + J_w^T I_W^-1 J_w; the least moment bounds the second term.
    const double bound = sumOverBodies(block,
                                       [&](std::size_t i, const Vec6& row)
                                       {
                                           return row.head<3>().squaredNorm() / rows.mass[i] +
                                                  row.tail<3>().squaredNorm() / principal[i].moments(0);
                                       });
    if (delassus >= ratio * bound)
    {
        return false;
    }
    const double free =
        sumOverBodies(block, [&](std::size_t i, const Vec6& row) { return freeDelassus(rows, i, row); });
    return delassus < ratio * free;
}

double displacementScale(const Model& model, const BlockVector& displacement, double maxTranslation,
                         double maxRotation)
{
    double scale = 1.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (model.bodies[i].isStatic)
        {
            continue;
        }
        const double translation = displacement.body[i].head<3>().norm();
        const double rotation = displacement.body[i].tail<3>().norm();
        if (translation > maxTranslation)
        {
            scale = std::min(scale, maxTranslation / translation);
        }
        if (rotation > maxRotation)
        {
            scale = std::min(scale, maxRotation / rotation);
        }
    }
    return scale;
}

double largestRotation(const Model& model, const BlockVector& displacement)
{
    double largest = 0.0;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            largest = std::max(largest, displacement.body[i].tail<3>().norm());
        }
    }
    return largest;
}

} // namespace frontier::core
