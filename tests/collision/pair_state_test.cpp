// tests/collision/pair_state_test.cpp: what the detector keeps per shape pair between calls
// (collision/README.md "Per-pair state") only ever skips work whose outcome it proves. Oracle: a
// fresh detector, built for each state alone, on recorded runs of piles of hulls and of mixed
// shapes; the detector that saw every state before gives the same contacts, bit for bit, in the
// recorded order, backwards, and in jumps, and does fewer narrowphase tests.
#include "core/simulator.h"
#include "core/state.h"
#include "test_models.h"

#include <gtest/gtest.h>

namespace frontier::collision::test
{
namespace
{

constexpr double cPairStepS = 0.001; // s

// Rocks (non-convex meshes: hull pairs through FCL) dropped in a block onto the floor.
core::Model rockPile()
{
    core::Model model;
    model.simulation.dt = cPairStepS;
    model.bodies.push_back(floorBody());
    for (int k = 0; k < 8; ++k)
        model.bodies.push_back(movingMesh("rock" + std::to_string(k),
                                          rockMesh(0.07, 8, 12, 0.2, static_cast<unsigned>(k)),
                                          Vec3(0.15 * (k % 2), 0.15 * ((k / 2) % 2), 0.1 + 0.16 * (k / 4)),
                                          1000.0, rotation(0.5 * k, Vec3(1, 0.3 * k, 0.2))));
    return model;
}

// Boxes, capsules, cylinders, spheres and a hull dropped onto each other, some of them fast.
core::Model mixedPile()
{
    core::Model model;
    model.simulation.dt = cPairStepS;
    model.bodies.push_back(floorBody());
    const core::Shape shapes[] = {box(0.2, 0.1, 0.08), capsule(0.04, 0.2),  cylinder(0.05, 0.12),
                                  sphere(0.05),        box(0.1, 0.1, 0.1),  cubeMesh(0.09),
                                  capsule(0.03, 0.25), cylinder(0.04, 0.2), rockMesh(0.06, 8, 12, 0.2, 5)};
    int k = 0;
    for (const core::Shape& shape : shapes)
    {
        core::Body b = moving("body" + std::to_string(k), shape,
                              Vec3(0.12 * (k % 3), 0.1 * ((k / 3) % 3), 0.1 + 0.13 * k),
                              rotation(0.7 * k + 0.3, Vec3(1, 0.5 * k, 0.3)));
        b.velocity_W = Vec3(0.0, 0.0, k % 4 == 3 ? -8.0 : 0.0); // a few fast enough to be swept
        model.bodies.push_back(b);
        ++k;
    }
    return model;
}

std::vector<core::State> record(const core::Model& model, int steps)
{
    ContactDetector detector(model, contactMargin(cPairStepS));
    detector.setStepTime(cPairStepS);
    core::Simulator simulator(model, {}, &detector);
    core::State state = core::initialState(model);
    std::vector<core::State> states{state};
    for (int k = 0; k < steps; ++k)
    {
        simulator.step(state);
        states.push_back(state);
    }
    return states;
}

void expectSame(const std::vector<Contact>& kept, const std::vector<Contact>& fresh, std::size_t at)
{
    ASSERT_EQ(kept.size(), fresh.size()) << "state " << at;
    for (std::size_t c = 0; c < kept.size(); ++c)
    {
        EXPECT_EQ(kept[c].bodyA, fresh[c].bodyA) << "state " << at;
        EXPECT_EQ(kept[c].bodyB, fresh[c].bodyB) << "state " << at;
        EXPECT_EQ(kept[c].point_W, fresh[c].point_W) << "state " << at;
        EXPECT_EQ(kept[c].normal_W, fresh[c].normal_W) << "state " << at;
        EXPECT_EQ(kept[c].depth, fresh[c].depth) << "state " << at;
    }
}

// The detector that saw the states before gives, on each state of `order`, what a fresh one gives.
void compareWithFresh(const core::Model& model, const std::vector<core::State>& states,
                      const std::vector<std::size_t>& order)
{
    ContactDetector kept(model, contactMargin(cPairStepS));
    kept.setStepTime(cPairStepS);
    long freshTests = 0;
    long contacts = 0;
    std::vector<Contact> a, b;
    for (const std::size_t k : order)
    {
        kept.detect(states[k], a);
        ContactDetector fresh(model, contactMargin(cPairStepS));
        fresh.setStepTime(cPairStepS);
        fresh.detect(states[k], b);
        freshTests += fresh.stats().narrowphaseTests;
        contacts += static_cast<long>(b.size());
        expectSame(a, b, k);
        if (testing::Test::HasFailure())
            return;
    }
    EXPECT_GT(contacts, static_cast<long>(order.size())); // the piles do touch
    // What the pair state is for: the proofs it keeps skip narrowphase tests a fresh detector does.
    EXPECT_LT(kept.stats().narrowphaseTests, freshTests);
}

void compareAllOrders(const core::Model& model, int steps)
{
    const std::vector<core::State> states = record(model, steps);
    std::vector<std::size_t> forward, backward, jumps;
    for (std::size_t k = 0; k < states.size(); ++k)
    {
        forward.push_back(k);
        backward.push_back(states.size() - 1 - k);
        jumps.push_back((k * 97) % states.size());
    }
    {
        SCOPED_TRACE("in the recorded order");
        compareWithFresh(model, states, forward);
    }
    {
        SCOPED_TRACE("backwards");
        compareWithFresh(model, states, backward);
    }
    {
        SCOPED_TRACE("in jumps");
        compareWithFresh(model, states, jumps);
    }
}

TEST(PairState, HullPileGivesWhatAFreshDetectorGives)
{
    compareAllOrders(rockPile(), 600);
}

TEST(PairState, MixedPileGivesWhatAFreshDetectorGives)
{
    compareAllOrders(mixedPile(), 600);
}

} // namespace
} // namespace frontier::collision::test
