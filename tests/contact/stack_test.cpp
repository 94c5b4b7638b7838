// tests/contact/stack_test.cpp: scenes/box_stack.yaml, five 10 cm boxes on the floor with 0.5 mm
// gaps, must settle and stand.
#include "contact_harness.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

// Bounds: after 5 s every box's centre within 5 mm (horizontally) of where it started, and the
// largest speed of any point of any box under 1e-3 m/s at the end; no box ever sinks more than
// 2 mm into the floor (plane penetration from the geometry).
TEST(BoxStack, FiveBoxesStandForFiveSeconds)
{
    SceneRun run(io::loadScene(scenePath("box_stack.yaml")));
    std::vector<Vec3> start;
    std::vector<int> boxes;
    for (int i = 0; i < 5; ++i)
    {
        boxes.push_back(run.model.findBody("box" + std::to_string(i)));
        ASSERT_GE(boxes.back(), 0);
        start.push_back(run.state.bodies[static_cast<std::size_t>(boxes.back())].position_W);
    }
    double drift = 0.0, floorPenetration = 0.0, deepest = 0.0;
    int maxContacts = 0;
    const long steps = run.stepsFor(5.0);
    for (long k = 0; k < steps; ++k)
    {
        run.step();
        ASSERT_TRUE(allFinite(run.state)) << "step " << k;
        floorPenetration = std::max(floorPenetration, planePenetration(run.model, run.state));
        deepest = std::max(deepest, run.simulator.lastStep().maxPenetrationM);
        maxContacts = std::max(maxContacts, run.simulator.lastStep().contacts);
        for (std::size_t b = 0; b < boxes.size(); ++b)
        {
            const Vec3 d = run.state.bodies[static_cast<std::size_t>(boxes[b])].position_W - start[b];
            drift = std::max(drift, std::hypot(d.x(), d.y()));
        }
    }
    const double speed = maxPointSpeed(run.model, run.state);
    double settle = 0.0; // how far each box came down (the gaps close): about 0.5 mm per gap below it
    for (std::size_t b = 0; b < boxes.size(); ++b)
    {
        settle = std::max(settle,
                          start[b].z() - run.state.bodies[static_cast<std::size_t>(boxes[b])].position_W.z());
    }
    std::printf("box stack: drift %.3g m, final speed %.3g m/s, settled by %.3g m, floor penetration %.3g m, "
                "deepest contact %.3g m, max contacts %d\n",
                drift, speed, settle, floorPenetration, deepest, maxContacts);
    EXPECT_LT(drift, 5e-3);
    EXPECT_LT(speed, 1e-3);
    EXPECT_LT(floorPenetration, 2e-3);
    // The four gaps close (2 mm in all for the top box) and nothing sinks further: the top box
    // comes down by 2 mm plus at most the 0.5 mm slop per contact layer.
    EXPECT_LT(settle, 2e-3 + 5 * 5e-4);
    // Each box stays level: resting contact tolerates overlap up to the 0.5 mm slop, so a face
    // on a face can settle tilted by up to slop / half-width = 0.5 mm / 50 mm = 10 mrad; measured
    // 1.6 mrad at most. Half that allowance catches a box that starts to rock or topple.
    for (int i = 0; i < 5; ++i)
    {
        EXPECT_LT(run.body("box" + std::to_string(i)).orientation_WB.angularDistance(core::Quat::Identity()),
                  5e-3)
            << "box" << i << " tilted (rad)";
    }
}

} // namespace
} // namespace frontier::test
