// bench/peers/jitter.cpp
#include "bench/peers/jitter.h"

#include "bench/peers/contacts.h"

#include <Eigen/Geometry>
#include <numeric>
#include <random>
#include <stdexcept>

namespace frontier::peers
{
namespace
{

// A uniform number in [0, 1) from the generator's next 53 bits (not std::uniform_real_distribution,
// whose results differ between standard libraries).
double uniform(std::mt19937_64& random)
{
    return static_cast<double>(random() >> 11) * 0x1.0p-53;
}

double symmetric(std::mt19937_64& random, double bound)
{
    return bound * (2.0 * uniform(random) - 1.0);
}

// The deepest overlap (m) at the model's start, with the bodies at the given poses.
double startOverlap(const core::Model& model, PenetrationMeter& meter)
{
    std::vector<Pose> poses(model.bodies.size());
    for (std::size_t b = 0; b < poses.size(); ++b)
        poses[b] = {model.bodies[b].position_W, model.bodies[b].orientation_WB};
    return meter.deepest(poses);
}

// The representative of b's set (union-find with path halving).
int find(std::vector<int>& parent, int b)
{
    const auto at = [&parent](int i) -> int& { return parent[static_cast<std::size_t>(i)]; };
    while (at(b) != b)
    {
        at(b) = at(at(b));
        b = at(b);
    }
    return b;
}

} // namespace

std::vector<std::vector<int>> freeTrees(const core::Model& model)
{
    const int n = static_cast<int>(model.bodies.size());
    std::vector<int> parent(static_cast<std::size_t>(n));
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> anchored(static_cast<std::size_t>(n), 0);
    for (const core::Joint& joint : model.joints)
    {
        if (!isMovingBody(model, joint.parent))
        {
            anchored[static_cast<std::size_t>(joint.child)] = 1;
            continue;
        }
        parent[static_cast<std::size_t>(find(parent, joint.parent))] = find(parent, joint.child);
    }
    std::vector<char> anchoredRoot(static_cast<std::size_t>(n), 0);
    for (int b = 0; b < n; ++b)
        if (anchored[static_cast<std::size_t>(b)])
            anchoredRoot[static_cast<std::size_t>(find(parent, b))] = 1;
    std::vector<std::vector<int>> trees;
    std::vector<int> treeOf(static_cast<std::size_t>(n), -1); // by root
    for (int b = 0; b < n; ++b)
    {
        const int root = find(parent, b);
        if (model.bodies[static_cast<std::size_t>(b)].isStatic ||
            anchoredRoot[static_cast<std::size_t>(root)])
            continue;
        int& tree = treeOf[static_cast<std::size_t>(root)];
        if (tree < 0)
        {
            tree = static_cast<int>(trees.size());
            trees.emplace_back();
        }
        trees[static_cast<std::size_t>(tree)].push_back(b);
    }
    return trees;
}

std::vector<core::Model> jitteredVariants(const core::Model& model, int count, std::uint64_t seed,
                                          const JitterBounds& bounds)
{
    constexpr double cOverlapToleranceM = 1e-12; // the detector's round-off on an unchanged contact
    constexpr int cAttempts = 100;
    const std::vector<std::vector<int>> trees = freeTrees(model);
    PenetrationMeter meter(model);
    const double allowed = startOverlap(model, meter) + cOverlapToleranceM;
    std::mt19937_64 random(seed);
    std::vector<core::Model> variants;
    for (int v = 0; v < count; ++v)
    {
        for (int attempt = 0;; ++attempt)
        {
            if (attempt == cAttempts)
                throw std::runtime_error("variant " + std::to_string(v + 1) + ": " +
                                         std::to_string(cAttempts) +
                                         " jittered starts in a row overlap more than the scene's own start");
            core::Model variant = model;
            for (const std::vector<int>& tree : trees)
            {
                const core::Vec3 shift(symmetric(random, bounds.horizontalM),
                                       symmetric(random, bounds.horizontalM), bounds.upM * uniform(random));
                const core::Quat yaw(
                    Eigen::AngleAxisd(symmetric(random, bounds.yawRad), core::Vec3::UnitZ()));
                double mass = 0.0;
                core::Vec3 centre = core::Vec3::Zero();
                for (int b : tree)
                {
                    const core::Body& body = model.bodies[static_cast<std::size_t>(b)];
                    mass += body.mass;
                    centre += body.mass * body.position_W;
                }
                centre /= mass;
                for (int b : tree)
                {
                    core::Body& body = variant.bodies[static_cast<std::size_t>(b)];
                    body.position_W = centre + yaw * (body.position_W - centre) + shift;
                    body.orientation_WB = (yaw * body.orientation_WB).normalized();
                    body.velocity_W = yaw * body.velocity_W;
                    body.angularVelocity_W = yaw * body.angularVelocity_W;
                }
            }
            if (startOverlap(variant, meter) <= allowed)
            {
                variants.push_back(std::move(variant));
                break;
            }
        }
    }
    return variants;
}

} // namespace frontier::peers
