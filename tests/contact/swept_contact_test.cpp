// tests/contact/swept_contact_test.cpp: the swept search of fast bodies (docs/method.md §10). A
// body travelling more than half the contact margin in a step is searched along its motion, so
// what lies in its path is found at the step start as a gap contact; what it passes by is not.
#include "contact_harness.h"

#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::test
{
namespace
{

// A 1 cm steel ball in zero gravity at `position` with `velocity`, and a static wall 1 cm thick
// (x), 1 m wide (y) and high (z), centred at (1, 0, 1): scenes/stability/tunnelling.yaml's.
core::Model ballAndWall(const Vec3& position, const Vec3& velocity, core::SolverKind solver, double dt)
{
    std::ostringstream y;
    y.precision(17);
    y << "name: swept ball\nsimulation: {dt: " << dt << ", duration: 0.02, gravity: [0, 0, 0]}\n"
      << "contact: {friction: 0.0, restitution: 0.5}\nbodies:\n"
      << "  - {name: bullet, shape: {type: sphere, radius: 0.01}, density: 7800, position: [" << position.x()
      << ", " << position.y() << ", " << position.z() << "], velocity: [" << velocity.x() << ", "
      << velocity.y() << ", " << velocity.z() << "]}\n"
      << "  - {name: wall, static: true, shape: {type: box, size: [0.01, 1, 1]}, position: [1.0, 0, 1]}\n";
    core::Model model = io::loadSceneFromString(y.str(), "swept_contact_test");
    model.simulation.solver = solver;
    return model;
}

// The ball of tunnelling.yaml (300 m/s, 30 cm a step at dt = 1 ms, against a wall 1 cm thick)
// bounces off the wall with restitution 0.5, with the linear solver and with pgs: the swept
// search finds the wall in its path a step before, and the row lets it close the gap, not pass it.
TEST(SweptContact, FastBallBouncesOffThinWall)
{
    for (const core::SolverKind solver : {core::SolverKind::Linear, core::SolverKind::Pgs})
    {
        SceneRun run(ballAndWall(Vec3(0, 0, 1), Vec3(300, 0, 0), solver, 1e-3));
        double maxX = -1.0; // m
        for (long k = 0; k < run.stepsFor(0.02); ++k)
        {
            run.step();
            maxX = std::max(maxX, run.body("bullet").position_W.x());
        }
        const core::BodyState& ball = run.body("bullet");
        std::printf("%s: ball at x = %.4f m (nearest the wall %.4f), v = %.6g m/s\n",
                    core::solverName(solver), ball.position_W.x(), maxX, ball.velocity_W.x());
        EXPECT_LT(maxX, 1.0 - 0.005 - 0.01 + 1e-3) << "the ball reached into the wall";
        EXPECT_NEAR(ball.velocity_W.x(), -150.0, 1e-6); // restitution 0.5
        EXPECT_LT(ball.position_W.x(), 0.0);
        EXPECT_NEAR(ball.velocity_W.y(), 0.0, 1e-9);
        EXPECT_NEAR(ball.velocity_W.z(), 0.0, 1e-9);
    }
}

// The same wall as a static triangle mesh (FCL's BVH; its nearest points come in the frames of
// the mesh and the ball): the ball bounces off it as off the box.
TEST(SweptContact, FastBallBouncesOffMeshWall)
{
    core::Model model = ballAndWall(Vec3(0, 0, 1), Vec3(300, 0, 0), core::SolverKind::Linear, 1e-3);
    core::Shape& wall = model.bodies[static_cast<std::size_t>(model.findBody("wall"))].shapes.at(0);
    const Vec3 half = 0.5 * wall.size;
    wall.type = core::ShapeType::Mesh;
    for (int k = 0; k < 8; ++k)
        wall.vertices.emplace_back((k & 1) ? half.x() : -half.x(), (k & 2) ? half.y() : -half.y(),
                                   (k & 4) ? half.z() : -half.z());
    wall.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                      {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    SceneRun run(std::move(model));
    double maxX = -1.0; // m
    for (long k = 0; k < run.stepsFor(0.02); ++k)
    {
        run.step();
        maxX = std::max(maxX, run.body("bullet").position_W.x());
    }
    EXPECT_LT(maxX, 0.985);
    EXPECT_NEAR(run.body("bullet").velocity_W.x(), -150.0, 1e-6);
}

// Two moving bodies: the ball at 150 m/s against a free plate 4 mm thick coming at 150 m/s (30 cm
// a step between them at dt = 1 ms), restitution 1. Both are swept along their own motion; they
// meet and leave with the velocities of a 1-d elastic collision, momentum and energy kept.
TEST(SweptContact, FastBallAndFastPlateCollideElastically)
{
    const std::string yaml =
        "name: two fast bodies\nsimulation: {dt: 0.001, duration: 0.02, gravity: [0, 0, 0]}\n"
        "contact: {friction: 0.0, restitution: 1.0}\nbodies:\n"
        "  - {name: ball, shape: {type: sphere, radius: 0.01}, density: 7800, position: [0, 0, 1],"
        " velocity: [150, 0, 0]}\n"
        "  - {name: plate, shape: {type: box, size: [0.004, 0.1, 0.1]}, density: 7800, position: [1, 0, 1],"
        " velocity: [-150, 0, 0]}\n";
    SceneRun run(io::loadSceneFromString(yaml, "swept_contact_test"));
    const double ma = run.model.bodies[static_cast<std::size_t>(run.model.findBody("ball"))].mass; // kg
    const double mb = run.model.bodies[static_cast<std::size_t>(run.model.findBody("plate"))].mass;
    for (long k = 0; k < run.stepsFor(0.02); ++k)
        run.step();
    const double va = ((ma - mb) * 150.0 - 2.0 * mb * 150.0) / (ma + mb); // m/s
    const double vb = (-(mb - ma) * 150.0 + 2.0 * ma * 150.0) / (ma + mb);
    EXPECT_NEAR(run.body("ball").velocity_W.x(), va, 1e-6);
    EXPECT_NEAR(run.body("plate").velocity_W.x(), vb, 1e-6);
    EXPECT_LT(run.body("ball").position_W.x(), run.body("plate").position_W.x()); // not through
}

// Fast balls that pass the wall by are not disturbed: past its edge (1 cm clear, the nearest point
// at the step start is the wall's edge, ahead of the ball) and along its face (1 cm clear). Their
// trajectories are free flight to round-off.
TEST(SweptContact, FastBallPassingByIsNotDisturbed)
{
    struct Pass
    {
        Vec3 position, velocity;
    };
    const Pass passes[] = {
        {Vec3(0, 0.52, 1), Vec3(300, 0, 0)},     // past the edge at y = 0.5
        {Vec3(0.975, -1.5, 1), Vec3(0, 300, 0)}, // along the face at x = 0.995
        {Vec3(0, 0.52, 1), Vec3(300, -0.3, 0)},  // past the edge, slightly towards it
        {Vec3(1.0, 0, 1.53), Vec3(300, 0, 0)},   // over the top, starting above it
    };
    for (const Pass& pass : passes)
    {
        SceneRun run(ballAndWall(pass.position, pass.velocity, core::SolverKind::Linear, 1e-3));
        const long steps = run.stepsFor(0.01);
        for (long k = 0; k < steps; ++k)
            run.step();
        const core::BodyState& ball = run.body("bullet");
        const Vec3 free = pass.position + pass.velocity * (static_cast<double>(steps) * 1e-3);
        EXPECT_LT((ball.position_W - free).norm(), 1e-9) << pass.position.transpose();
        EXPECT_EQ(ball.velocity_W, pass.velocity) << pass.position.transpose();
    }
}

// A rod 1 m long, 2 cm thick, spinning at 60 rad/s about a horizontal axis with its centre 0.2 m
// above the floor, at dt = 10 ms: its ends move 30 cm a step, six times the 5 cm margin, and would
// sweep 31 cm below the floor. The swept search finds the end in its path (the window of the plane
// grows by the turn's reach, |w| dt r): no step starts with it more than 1 cm into the floor
// (measured 0; without the sweep 9.3 cm).
TEST(SweptContact, SpinningRodDoesNotTunnelIntoFloor)
{
    std::ostringstream y;
    y << "name: spinning rod\nsimulation: {dt: 0.01, duration: 0.5}\n"
      << "contact: {friction: 0.5, restitution: 0.0}\nbodies:\n"
      << "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n"
      << "  - {name: rod, shape: {type: capsule, radius: 0.01, length: 1.0}, mass: 1.0, position: [0, 0, "
         "0.2],"
      << " orientation: [0.7071067811865476, 0, 0.7071067811865476, 0], angular_velocity: [0, 60, 0]}\n";
    double deepest[2] = {0.0, 0.0}; // m: swept, not swept
    for (const bool swept : {true, false})
    {
        SceneRun run(io::loadSceneFromString(y.str(), "swept_contact_test"));
        if (!swept)
            run.detector.setStepTime(0.0);
        for (long k = 0; k < run.stepsFor(0.5); ++k)
        {
            run.step();
            // The deepest overlap a step starts with (the projection removes it within the step).
            deepest[swept ? 0 : 1] =
                std::max(deepest[swept ? 0 : 1], run.simulator.lastStep().maxPenetrationM);
        }
        EXPECT_TRUE(allFinite(run.state));
        EXPECT_GT(run.body("rod").position_W.z(), 0.0);
    }
    std::printf("spinning rod: deepest %.4g m into the floor swept, %.4g m not\n", deepest[0], deepest[1]);
    EXPECT_LT(deepest[0], 0.01);
    EXPECT_GT(deepest[1], 0.05); // the scene needs the sweep
}

} // namespace
} // namespace frontier::test
