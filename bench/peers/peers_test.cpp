// bench/peers/peers_test.cpp: the peers run the same physics as Frontier. Each engine steps small
// chains (ball joints, hinges, a weld, a free root) for 0.2 s at dt = 1 ms, and its bodies must end
// near Frontier's fine-step RATTLE reference (dt / 16), with the joint gaps each kind of method
// allows: reduced coordinates none, Frontier round-off, the others the drift their solvers leave.
#include "bench/peers/chain.h"
#include "bench/peers/engine.h"
#include "bench/peers/measures.h"

#include <gtest/gtest.h>

namespace frontier::peers
{
namespace
{

std::vector<Pose> runFor(Engine& engine, long steps)
{
    for (long k = 0; k < steps; ++k)
        engine.step();
    std::vector<Pose> poses;
    engine.poses(poses);
    return poses;
}

// A hinge chain with a weld in the middle, swinging about y.
core::Model hingeChainWithWeld()
{
    core::Model model = chainOfBoxes(5);
    for (core::Joint& joint : model.joints)
    {
        joint.type = core::JointType::Revolute;
        joint.axisParent = joint.axisChild = core::Vec3::UnitY();
        joint.perpParent1 = joint.perpChild1 = core::Vec3::UnitZ();
        joint.perpParent2 = core::Vec3::UnitX();
    }
    model.joints[2].type = core::JointType::Fixed;
    return model;
}

// The ball chain with no joint to the world, tumbling: a free root.
core::Model freeChain()
{
    core::Model model = chainOfBoxes(4, 3.0);
    model.joints.erase(model.joints.begin());
    model.simulation.gravity = core::Vec3(0.0, 0.0, -9.81);
    return model;
}

struct Case
{
    const char* name;
    core::Model model;
};

void expectAgreement(const Case& c)
{
    constexpr long cSteps = 200;
    core::Model fine = c.model;
    fine.simulation.dt /= 16.0;
    const auto reference = runFor(*makeFrontier(fine, core::IntegratorKind::Rattle), 16 * cSteps);
    for (const std::string& name : engineNames())
    {
        SCOPED_TRACE(std::string(c.name) + ", " + name);
        const auto engine = makeEngine(name, c.model);
        std::vector<Pose> start;
        engine->poses(start);
        EXPECT_LT(positionError(start, runFor(*makeFrontier(c.model, core::IntegratorKind::Euler), 0)),
                  1e-12);
        const auto end = runFor(*engine, cSteps);
        // 0.2 s of swinging moves the tip about 0.2 m; a wrong anchor, axis or inertia moves it by
        // centimetres, a first-order method at 1 ms by millimetres.
        EXPECT_LT(positionError(end, reference), 5e-3);
        const bool reduced = name == "bullet-multibody" || name == "mujoco";
        const bool frontier = name.rfind("frontier", 0) == 0;
        EXPECT_LT(jointGap(c.model, end), reduced ? 1e-12 : frontier ? 1e-9 : 5e-3);
    }
}

TEST(Peers, BallChainAgreesWithTheReferenceInEveryEngine)
{
    expectAgreement({"ball chain", chainOfBoxes(6)});
}

TEST(Peers, HingeChainWithAWeldAgreesInEveryEngine)
{
    expectAgreement({"hinge chain", hingeChainWithWeld()});
}

TEST(Peers, FreeChainAgreesInEveryEngine)
{
    expectAgreement({"free chain", freeChain()});
}

TEST(Peers, OutOfScopeModelsAreRefusedWithAReason)
{
    core::Model model = chainOfBoxes(3);
    model.joints[1].type = core::JointType::Prismatic;
    for (const std::string& name : engineNames())
    {
        if (name.rfind("frontier", 0) == 0)
            continue; // Frontier runs every model
        try
        {
            makeEngine(name, model);
            ADD_FAILURE() << name << " accepted a prismatic joint";
        }
        catch (const Unsupported& e)
        {
            EXPECT_NE(std::string(e.what()).find("joint1"), std::string::npos) << e.what();
        }
    }
}

} // namespace
} // namespace frontier::peers
