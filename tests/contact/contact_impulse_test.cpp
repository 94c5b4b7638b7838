// tests/contact/contact_impulse_test.cpp: the impulses the contacts of a step passed
// (core::Simulator::contactImpulses; the `--contacts` file), against Newton's second law and statics:
// - a box resting on the floor: its contacts' impulses are its change of momentum less its weight
//   in every step, and over a second their normal impulses hold its weight, m g;
// - the box stack and the falling doll (contacts between moving bodies, joints and contacts
//   together; euler and rattle): every body changes its momentum by gravity, its joints' and its
//   contacts' impulses, to round-off;
// - every contact pushes (normal impulse >= 0) and its friction stays within the Coulomb cone.
#include "contact_harness.h"
#include "momentum_balance.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace frontier::test
{
namespace
{

constexpr double cG = 9.81; // m/s^2

// A 2 kg box 0.2 m wide resting on the floor, its bottom face on z = 0.
core::Model boxOnFloor(core::IntegratorKind integrator)
{
    core::Model model = io::loadSceneFromString(R"(
simulation: {dt: 0.001, gravity: [0, 0, -9.81]}
contact: {friction: 0.5}
bodies:
  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}
  - {name: box, mass: 2.0, shape: {type: box, size: [0.2, 0.2, 0.2]}, position: [0, 0, 0.1]}
)",
                                                "box_on_floor");
    model.simulation.integrator = integrator;
    return model;
}

// Steps a run `steps` times; after each step, `see(step, residual, contacts)` with the step's
// contacts and its residual of Newton's second law (momentum_balance.h). Stops at the first
// fatal failure.
template <class See> void stepAndSee(SceneRun& run, long steps, See&& see)
{
    std::vector<core::ContactImpulse> contacts;
    std::vector<core::Vec6> joints;
    for (long step = 0; step < steps && !::testing::Test::HasFatalFailure(); ++step)
    {
        const core::State before = run.state;
        run.step();
        run.simulator.contactImpulses(contacts);
        run.simulator.jointChildImpulses(run.state, joints);
        see(step, secondLawResidual(run.model, before, run.state, joints, contacts), contacts);
    }
}

class ContactImpulses : public ::testing::TestWithParam<core::IntegratorKind>
{
};

// Over the second after 0.2 s of settling the box rests: the contact solve leaves it moving by up
// to its tolerance (3e-5 m/s), and those changes of momentum cancel over the second but for the
// first and the last, so the normal impulses of the second are m g (1 s) within 2 m 3e-5 N s.
TEST_P(ContactImpulses, BoxOnTheFloorIsHeldUpByItsWeight)
{
    SceneRun run(boxOnFloor(GetParam()));
    const int box = run.model.findBody("box");
    const double m = 2.0;
    double normal = 0.0; // N s over the second
    long rows = 0;
    stepAndSee(
        run, 1200,
        [&](long step, const SecondLawResidual& residual, const std::vector<core::ContactImpulse>& contacts)
        {
            ASSERT_EQ(static_cast<int>(contacts.size()), run.simulator.lastStep().contacts);
            ASSERT_LE(residual.relative, 1e-12) << "step " << step;
            for (const core::ContactImpulse& c : contacts)
            {
                ASSERT_TRUE(c.contact.bodyA == box || c.contact.bodyB == box);
                ASSERT_GE(c.normalImpulse(), 0.0) << "step " << step;
                ASSERT_LE(c.frictionImpulse_W().norm(), 0.5 * c.normalImpulse() * (1.0 + 1e-9) + 1e-15)
                    << "step " << step;
                ASSERT_LE(std::abs(c.frictionImpulse_W().dot(c.contact.normal_W)), 1e-15) << "step " << step;
                normal += step >= 200 ? c.normalImpulse() : 0.0;
            }
            rows += step >= 200 ? static_cast<long>(contacts.size()) : 0;
        });
    EXPECT_GE(rows, 4 * 1000) << "a resting box has its four corners in contact";
    EXPECT_NEAR(normal, m * cG * 1.0, 2.0 * m * 3e-5);
}

// Contacts between moving bodies (the stack) and joints with contacts (the doll landing).
// Residuals measured: 4e-15 (stack), 6e-13 (doll) of the step's largest impulse.
TEST_P(ContactImpulses, StackAndDollBodiesMoveByTheirImpulses)
{
    for (const char* scene : {"box_stack.yaml", "falling_doll.yaml"})
    {
        core::Model model = io::loadScene(scenePath(scene));
        model.simulation.integrator = GetParam();
        SceneRun run(std::move(model));
        double worst = 0.0;
        long pushing = 0;
        stepAndSee(run, 1000,
                   [&](long step, const SecondLawResidual& residual,
                       const std::vector<core::ContactImpulse>& contacts)
                   {
                       worst = std::max(worst, residual.relative);
                       ASSERT_LE(residual.relative, 5e-12)
                           << scene << ": body '" << residual.body << "', step " << step;
                       for (const core::ContactImpulse& c : contacts)
                       {
                           ASSERT_GE(c.normalImpulse(), 0.0) << scene << ", step " << step;
                           ASSERT_LE(c.frictionImpulse_W().norm(),
                                     run.model.contact.friction * c.normalImpulse() * (1.0 + 1e-6) + 1e-12)
                               << scene << ", step " << step;
                           pushing += c.normalImpulse() > 0.0 ? 1 : 0;
                       }
                   });
        EXPECT_GT(pushing, 1000) << scene;
        char text[32];
        std::snprintf(text, sizeof text, "%.3g", worst);
        RecordProperty(scene, text);
    }
}

INSTANTIATE_TEST_SUITE_P(Contact, ContactImpulses,
                         ::testing::Values(core::IntegratorKind::Euler, core::IntegratorKind::Rattle));

} // namespace
} // namespace frontier::test
