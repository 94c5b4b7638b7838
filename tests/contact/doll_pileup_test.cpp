// tests/contact/doll_pileup_test.cpp: articulated bodies falling onto the floor and onto each
// other: scenes/falling_doll.yaml (the paper's figure 8), scenes/pileup44.yaml (figure 7) and
// scenes/doll_urdf_scene.yaml (two URDF dolls). Run to the end, each step checked.
#include "contact_harness.h"
#include "tests/soak.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace frontier::test
{
namespace
{

struct RunRecord
{
    long steps = 0;
    bool finite = true;
    double maxContactDepth = 0.0;     // lastStep().maxPenetrationM: deepest contact the detector saw (m)
    double maxPlanePenetration = 0.0; // from the geometry, end of every step (m)
    double maxJointError = 0.0;       // m, every step
    double energyStart = 0.0;         // J
    double maxEnergyRise = 0.0;       // max over steps of E - E_start (J)
    double maxStepEnergyRise = 0.0;   // largest E_k - E_(k-1) (J)
    int maxContacts = 0;
    int maxSweeps = 0;
    double endPointSpeed = 0.0;  // largest point speed at the end (m/s)
    double endLinearSpeed = 0.0; // largest centre-of-mass speed at the end (m/s)
};

RunRecord runScene(SceneRun& run, double seconds)
{
    RunRecord r;
    r.energyStart = core::totalEnergy(run.model, run.state);
    double previous = r.energyStart;
    const long steps = run.stepsFor(seconds);
    for (long k = 0; k < steps; ++k)
    {
        try
        {
            run.step();
        }
        catch (const core::SimulationError& error)
        {
            ADD_FAILURE() << error.what();
            r.finite = false;
            break;
        }
        r.steps = k + 1;
        if (!allFinite(run.state))
        {
            r.finite = false;
            break;
        }
        const core::StepStats& st = run.simulator.lastStep();
        r.maxContactDepth = std::max(r.maxContactDepth, st.maxPenetrationM);
        r.maxPlanePenetration = std::max(r.maxPlanePenetration, planePenetration(run.model, run.state));
        r.maxJointError = std::max(r.maxJointError, st.maxJointErrorM);
        r.maxContacts = std::max(r.maxContacts, st.contacts);
        r.maxSweeps = std::max(r.maxSweeps, st.contactSweeps);
        const double energy = core::totalEnergy(run.model, run.state);
        r.maxEnergyRise = std::max(r.maxEnergyRise, energy - r.energyStart);
        r.maxStepEnergyRise = std::max(r.maxStepEnergyRise, energy - previous);
        previous = energy;
    }
    r.endPointSpeed = maxPointSpeed(run.model, run.state);
    r.endLinearSpeed = maxLinearSpeed(run.model, run.state);
    return r;
}

void print(const char* name, const RunRecord& r)
{
    std::printf(
        "%s: %ld steps, contacts <= %d, sweeps <= %d, deepest contact %.3g m, plane penetration %.3g m, "
        "joint error %.3g m, energy %.6g J, max rise %.3g J (per step %.3g J), end speed %.3g m/s "
        "(centres %.3g m/s)\n",
        name, r.steps, r.maxContacts, r.maxSweeps, r.maxContactDepth, r.maxPlanePenetration, r.maxJointError,
        r.energyStart, r.maxEnergyRise, r.maxStepEnergyRise, r.endPointSpeed, r.endLinearSpeed);
}

// The falling doll (15 bodies, 14 joints of five types, friction 0.6, restitution 0.1), 3 s with
// the given integrator. Bounds: finite; penetration under `penetrationBound` (m) both as the
// detector's deepest contact and measured from the geometry against the floor after every step;
// joint error under 1e-6 m every step; the total energy never above its start by more than 1e-9
// relative (contacts only dissipate, and the penetration and joint projections are meant not to
// inject energy); after 3 s every point of every body slower than 1e-2 m/s (it lies still).
void checkDollComesToRest(core::IntegratorKind integrator, double penetrationBound, const char* label)
{
    core::Model model = io::loadScene(scenePath("falling_doll.yaml"));
    model.simulation.integrator = integrator;
    SceneRun run(std::move(model));
    ASSERT_EQ(run.model.bodies.size(), 16u); // 15 bodies and the floor
    const RunRecord r = runScene(run, 3.0);
    print(label, r);
    ASSERT_TRUE(r.finite);
    EXPECT_EQ(r.steps, 3000);
    EXPECT_LT(r.maxContactDepth, penetrationBound);
    EXPECT_LT(r.maxPlanePenetration, penetrationBound);
    EXPECT_LT(r.maxJointError, 1e-6);
    EXPECT_LE(r.maxEnergyRise, 1e-9 * std::abs(r.energyStart));
    EXPECT_LT(r.endPointSpeed, 1e-2);
    EXPECT_GT(r.maxContacts, 0);
}

// euler: penetration under 2 mm.
TEST(FallingDoll, LandsAndComesToRest)
{
    checkDollComesToRest(core::IntegratorKind::Euler, 2e-3, "falling doll");
}

// The second-order integrator (rattle): contacts, friction and the impacts act in its first stage,
// and contacts that pushed there hold (one-sided, with friction) in its final velocity projection,
// so it comes to rest the same way. Same bounds except penetration: 3 mm (measured 2.8 mm, at one
// impact of a limb at about 6 m/s, 0.62 s in; the projection's friction impulse, evaluated at the
// contact points of the step's start, turns a neighbouring point into the floor, and the next step
// removes it).
TEST(FallingDoll, LandsAndComesToRestWithRattle)
{
    checkDollComesToRest(core::IntegratorKind::Rattle, 3e-3, "falling doll, rattle");
}

// 44 capsules in four chains of 11 on ball joints, dropped crosswise onto each other and the
// floor, 5 s. Bounds: finite; penetration under 5 mm (detector and geometry); joint error under
// 1e-6 m every step; energy never above its start (1e-9 relative). A soak test: under the
// sanitizers reference.pileup44 (tests/references) runs the same 5000 steps.
TEST(Pileup44, PilesWithoutBlowingUp)
{
    FRONTIER_SOAK_TEST();
    SceneRun run(io::loadScene(scenePath("pileup44.yaml")));
    int moving = 0;
    for (const core::Body& b : run.model.bodies)
    {
        moving += b.isStatic ? 0 : 1;
    }
    ASSERT_EQ(moving, 44);
    const RunRecord r = runScene(run, 5.0);
    print("pileup44", r);
    ASSERT_TRUE(r.finite);
    EXPECT_EQ(r.steps, 5000);
    EXPECT_LT(r.maxContactDepth, 5e-3);
    EXPECT_LT(r.maxPlanePenetration, 5e-3);
    EXPECT_LT(r.maxJointError, 1e-6);
    EXPECT_LE(r.maxEnergyRise, 1e-9 * std::abs(r.energyStart));
    // The chains do pile: more than one contact per body at some step.
    EXPECT_GT(r.maxContacts, 44);
}

// Two URDF dolls (scenes/doll_urdf_scene.yaml): loads with prefixes, 3 s finite; floor
// penetration under 2 mm, joint error under 1e-6 m, energy never above its start. Body-body
// contacts are bounded by 5 mm only: URDF limbs are cylinders, and when a cylinder's rim presses
// into another cylinder's side FCL/libccd's EPA normal can be ~45 degrees off the true one (the
// collision feature code then keeps FCL's normal, collision/feature_manifold.cpp "On an edge"),
// so the overlap grows along the true normal while the solver separates along FCL's: measured
// 1.8 mm to 4.1 mm depending on round-off (the run is chaotic). Reported to collision/.
TEST(UrdfDolls, TwoInstancesFallOntoTheFloor)
{
    SceneRun run(io::loadScene(scenePath("doll_urdf_scene.yaml")));
    ASSERT_GE(run.model.findBody("a_pelvis"), 0);
    ASSERT_GE(run.model.findBody("b_pelvis"), 0);
    const RunRecord r = runScene(run, 3.0);
    print("two URDF dolls", r);
    ASSERT_TRUE(r.finite);
    EXPECT_LT(r.maxContactDepth, 5e-3);
    EXPECT_LT(r.maxPlanePenetration, 2e-3);
    EXPECT_LT(r.maxJointError, 1e-6);
    EXPECT_LE(r.maxEnergyRise, 1e-9 * std::abs(r.energyStart));
    // Both dolls end on the floor: pelvis below its 1 m (a_) and 1.4 m (b_) start.
    EXPECT_LT(run.body("a_pelvis").position_W.z(), 0.5);
    EXPECT_LT(run.body("b_pelvis").position_W.z(), 0.5);
}

} // namespace
} // namespace frontier::test
