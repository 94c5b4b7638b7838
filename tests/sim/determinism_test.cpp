// tests/sim/determinism_test.cpp: two runs of one scene give the same bits, with contacts (the
// falling doll on the floor) and without (the 30-link chain). Each run loads its own model and
// builds its own simulator and contact detector, so nothing depends on addresses or on state
// shared between runs.
#include "collision/contacts.h"
#include "sim_test_util.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <memory>
#include <vector>

namespace frontier::sim::test
{
namespace
{

struct Recording
{
    std::vector<core::State> states; // every 10th step and the last
    int maxContacts = 0;
};

// Runs `file` for `duration` seconds, with FCL contacts when asked (the margin `frontier run`
// uses: collision::contactMargin).
Recording simulate(const std::string& file, double duration, bool contacts)
{
    const core::Model model = loadBundled(file);
    std::unique_ptr<collision::ContactDetector> detector;
    if (contacts)
    {
        detector = std::make_unique<collision::ContactDetector>(
            model, collision::contactMargin(model.simulation.dt));
    }
    core::Simulator simulator(model, {}, detector.get());
    core::State state = core::initialState(model);
    Recording run;
    const long steps = stepsFor(duration, model.simulation.dt);
    for (long k = 0; k < steps; ++k)
    {
        simulator.step(state);
        run.maxContacts = std::max(run.maxContacts, simulator.lastStep().contacts);
        if (state.step % 10 == 0 || k + 1 == steps)
        {
            run.states.push_back(state);
        }
    }
    return run;
}

void expectIdentical(const Recording& a, const Recording& b)
{
    ASSERT_EQ(a.states.size(), b.states.size());
    ASSERT_FALSE(a.states.empty());
    for (std::size_t k = 0; k < a.states.size(); ++k)
    {
        ASSERT_TRUE(bitIdentical(a.states[k], b.states[k]))
            << "runs differ at step " << a.states[k].step << " by "
            << stateDifference(a.states[k], b.states[k]);
    }
    EXPECT_EQ(a.maxContacts, b.maxContacts);
}

TEST(Determinism, FallingDollWithContactsIsBitIdentical)
{
    const Recording a = simulate("falling_doll.yaml", 1.0, true);
    const Recording b = simulate("falling_doll.yaml", 1.0, true);
    // The doll hits the floor within the second: the contact path is exercised.
    EXPECT_GE(a.maxContacts, 2);
    expectIdentical(a, b);
}

TEST(Determinism, Chain30IsBitIdentical)
{
    const Recording a = simulate("chain30.yaml", 1.0, false);
    const Recording b = simulate("chain30.yaml", 1.0, false);
    expectIdentical(a, b);
}

// The comparison itself can fail: one ulp in one number is a difference.
TEST(Determinism, OneUlpIsADifference)
{
    const core::Model model = loadBundled("chain30.yaml");
    const core::State a = core::initialState(model);
    core::State b = a;
    ASSERT_TRUE(bitIdentical(a, b));
    b.bodies[17].angularVelocity_W.y() = std::nextafter(b.bodies[17].angularVelocity_W.y(), 1.0);
    EXPECT_FALSE(bitIdentical(a, b));
}

} // namespace
} // namespace frontier::sim::test
