// tests/collision/mesh_motion_test.cpp: moving meshes colliding as their convex hulls, stepped
// by core::Simulator with the margin `frontier run` uses (5 dt, at least 2 mm). A mesh cube comes
// to rest on the floor on at most four points; two non-convex rocks dropped onto each other
// never gain energy (each contact can only take it away: restitution 0); a run is bit-identical
// when repeated. Penetration and energy are measured from the state and the meshes themselves,
// not from the detector.
#include "core/simulator.h"
#include "core/state.h"
#include "test_models.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <limits>

namespace frontier::collision::test
{
namespace
{

constexpr double cDt = 0.001; // s

// A model with its detector, simulator and state (they keep references to the model).
struct MeshRun
{
    explicit MeshRun(core::Model m)
        : model(std::move(m)), detector(model, contactMargin(model.simulation.dt)),
          simulator(model, {}, &detector), state(core::initialState(model))
    {
    }
    MeshRun(const MeshRun&) = delete;
    MeshRun& operator=(const MeshRun&) = delete;

    core::Model model;
    ContactDetector detector;
    core::Simulator simulator;
    core::State state;
};

// Lowest height (m) over the mesh vertices of every moving body: below 0 is in the floor z <= 0.
double lowestVertexHeight(const core::Model& model, const core::State& state)
{
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
    {
        if (model.bodies[b].isStatic)
            continue;
        const core::BodyState& body = state.bodies[b];
        for (const core::Shape& shape : model.bodies[b].shapes)
            for (const Vec3& v : shape.vertices)
                lowest = std::min(lowest, (body.position_W +
                                           body.orientation_WB * (shape.position_BS + shape.rotation_BS * v))
                                              .z());
    }
    return lowest;
}

core::Model floorModel()
{
    core::Model model;
    model.simulation.dt = cDt;
    model.bodies.push_back(floorBody());
    return model;
}

TEST(MeshMotion, MeshCubeRestsOnTheFloor)
{
    core::Model model = floorModel();
    // 1 cm above the floor, tilted a little so that it lands on an edge and settles on its face.
    const Quat tilt = rotation(0.05, Vec3(1, 0.4, 0));
    double below = 0.0; // m, from the centre down to the lowest corner
    for (const Vec3& v : cubeMesh(0.2).vertices)
        below = std::max(below, -(tilt * v).z());
    model.bodies.push_back(movingMesh("cube", cubeMesh(0.2), Vec3(0, 0, below + 0.01), 1000.0, tilt));
    MeshRun run(std::move(model));
    ASSERT_GT(lowestVertexHeight(run.model, run.state), 0.0);
    int maxContacts = 0;
    const long steps = std::lround(1.0 / cDt);
    for (long k = 0; k < steps; ++k)
    {
        run.simulator.step(run.state);
        maxContacts = std::max(maxContacts, run.simulator.lastStep().contacts);
    }
    const core::BodyState& cube = run.state.bodies[1];
    const double penetration = -lowestVertexHeight(run.model, run.state);
    std::printf("mesh cube on the floor after 1 s: penetration %.3g m, speed %.3g m/s, tilt %.3g rad, "
                "max contacts %d\n",
                penetration, cube.velocity_W.norm(), cube.orientation_WB.angularDistance(Quat::Identity()),
                maxContacts);
    EXPECT_LE(maxContacts, 4);
    EXPECT_LT(penetration, 1e-3);
    EXPECT_LT(cube.velocity_W.norm(), 1e-2);
    EXPECT_LT(cube.angularVelocity_W.norm(), 1e-1);
    // Face down: one of its axes vertical.
    const core::Mat3 R = cube.orientation_WB.toRotationMatrix();
    EXPECT_GT(R.row(2).cwiseAbs().maxCoeff(), 1.0 - 1e-4);
}

// Two rocks (jittered spheres, non-convex meshes), the upper one dropped off-centre onto the
// lower one, which stands on the floor.
core::Model rockDrop()
{
    core::Model model = floorModel();
    const core::Shape lower = rockMesh(0.1, 8, 12, 0.2, 3);
    const core::Shape upper = rockMesh(0.08, 8, 12, 0.2, 11);
    model.bodies.push_back(movingMesh("lower", lower, Vec3(0, 0, 0.13)));
    model.bodies.push_back(
        movingMesh("upper", upper, Vec3(0.04, 0.02, 0.45), 1000.0, rotation(0.7, Vec3(1, 2, 3))));
    return model;
}

TEST(MeshMotion, RocksDroppedOntoEachOtherDoNotGainEnergy)
{
    MeshRun run(rockDrop());
    ASSERT_GT(lowestVertexHeight(run.model, run.state), 0.0);
    const double start = core::totalEnergy(run.model, run.state);
    ASSERT_GT(start, 0.0);
    double highest = start;
    long stepOfHighest = 0;
    int maxContacts = 0;
    double deepest = 0.0;
    const long steps = std::lround(2.0 / cDt);
    for (long k = 0; k < steps; ++k)
    {
        run.simulator.step(run.state);
        const double energy = core::totalEnergy(run.model, run.state);
        if (energy > highest)
        {
            highest = energy;
            stepOfHighest = k;
        }
        maxContacts = std::max(maxContacts, run.simulator.lastStep().contacts);
        deepest = std::max(deepest, run.simulator.lastStep().maxPenetrationM);
    }
    const double end = core::totalEnergy(run.model, run.state);
    std::printf("rocks: energy %.6g J at the start, %.6g J at most (step %ld), %.6g J at the end; "
                "max contacts %d, deepest contact %.3g m\n",
                start, highest, stepOfHighest, end, maxContacts, deepest);
    EXPECT_LE(highest, start * (1.0 + 1e-6));
    EXPECT_LT(end, start); // they did hit each other and the floor, and lost energy doing so
    EXPECT_LT(deepest, 5e-3);
}

TEST(MeshMotion, RepeatedRunIsBitIdentical)
{
    MeshRun first(rockDrop());
    MeshRun second(rockDrop());
    const long steps = std::lround(0.6 / cDt);
    for (long k = 0; k < steps; ++k)
    {
        first.simulator.step(first.state);
        second.simulator.step(second.state);
        ASSERT_EQ(first.simulator.lastStep().contacts, second.simulator.lastStep().contacts) << "step " << k;
    }
    for (std::size_t b = 0; b < first.state.bodies.size(); ++b)
    {
        const core::BodyState& p = first.state.bodies[b];
        const core::BodyState& q = second.state.bodies[b];
        EXPECT_EQ(p.position_W, q.position_W);
        EXPECT_EQ(p.orientation_WB.coeffs(), q.orientation_WB.coeffs());
        EXPECT_EQ(p.velocity_W, q.velocity_W);
        EXPECT_EQ(p.angularVelocity_W, q.angularVelocity_W);
    }
}

} // namespace
} // namespace frontier::collision::test
