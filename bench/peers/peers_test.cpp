// bench/peers/peers_test.cpp: the peers run the same physics as Frontier. Each engine steps small
// chains (ball joints, hinges, a weld, a free root) for 0.2 s at dt = 1 ms, and its bodies must end
// near Frontier's fine-step RATTLE reference (dt / 16), with the joint gaps each kind of method
// allows: reduced coordinates none, Frontier round-off, the others the drift their solvers leave.
// With contacts: a box dropped on the floor and a sphere sliding into rolling, in every engine.
#include "bench/peers/chain.h"
#include "bench/peers/contacts.h"
#include "bench/peers/engine.h"
#include "bench/peers/measures.h"

#include <cmath>
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
        const bool reduced = name == "bullet-multibody" || name.rfind("mujoco", 0) == 0;
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

void expectRefusedByEveryPeer(const core::Model& model, const std::string& what, const std::string& reason)
{
    for (const std::string& name : engineNames())
    {
        if (name.rfind("frontier", 0) == 0)
            continue; // Frontier runs every model
        try
        {
            makeEngine(name, model);
            ADD_FAILURE() << name << " accepted " << what;
        }
        catch (const Unsupported& e)
        {
            EXPECT_NE(std::string(e.what()).find("joint1"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
        }
    }
}

TEST(Peers, OutOfScopeModelsAreRefusedWithAReason)
{
    core::Model prismatic = chainOfBoxes(3);
    prismatic.joints[1].type = core::JointType::Prismatic;
    expectRefusedByEveryPeer(prismatic, "a prismatic joint", "ball, revolute, angle and fixed");
    // Joint damping would otherwise be dropped without a word by the engines that run the rest.
    core::Model damped = chainOfBoxes(3);
    damped.joints[1].damping = 0.1;
    expectRefusedByEveryPeer(damped, "joint damping", "damping or friction");
}

// A floor (static plane z = 0) and one moving body with the given shape, its centre at height z.
core::Model onFloor(const core::Shape& shape, double mass, const core::Mat3& inertia, double z)
{
    core::Model model;
    model.name = "one body on the floor";
    model.simulation.dt = 0.001;
    model.contact.friction = 0.5;
    core::Body floor;
    floor.name = "floor";
    floor.isStatic = true;
    core::Shape plane;
    plane.type = core::ShapeType::Plane;
    floor.shapes.push_back(plane);
    model.bodies.push_back(floor);
    core::Body body;
    body.name = "body";
    body.mass = mass;
    body.inertia_B = inertia;
    body.shapes.push_back(shape);
    body.position_W = core::Vec3(0.0, 0.0, z);
    model.bodies.push_back(body);
    return model;
}

struct ContactRun
{
    std::vector<Pose> before, end; // the poses one step before the end, and at the end
    double deepest = 0.0;          // m, over every step
};

ContactRun runWithPenetration(const core::Model& model, const std::string& name, long steps)
{
    const auto engine = makeEngine(name, model);
    PenetrationMeter meter(model);
    ContactRun run;
    for (long k = 0; k < steps; ++k)
    {
        engine->step();
        run.before = run.end;
        engine->poses(run.end);
        run.deepest = std::max(run.deepest, meter.deepest(run.end));
    }
    return run;
}

// A box 0.2 x 0.3 x 0.1 m, turned 90 degrees about x in its body (so 0.3 m tall) and 5 cm off the
// centre of mass along x and 3 cm along z, the body turned 0.3 rad about z, dropped 0.1 m: after
// 1 s it rests on a face, its shape's centre 0.15 m up. A wrong size, offset or shape rotation in
// an engine's translation moves that by centimetres; the contacts' compliance is allowed 2 mm,
// and 5 mm of overlap at any step (MuJoCo's soft contacts, time constant 0.02 s, take 1 cm at the
// 1.4 m/s impact: 15 mm for it, 2 mm at rest).
TEST(Peers, BoxDroppedOnTheFloorComesToRestOnItInEveryEngine)
{
    core::Shape box;
    box.type = core::ShapeType::Box;
    box.size = core::Vec3(0.2, 0.3, 0.1);
    box.position_BS = core::Vec3(0.05, 0.0, 0.03);
    box.rotation_BS = core::Quat(Eigen::AngleAxisd(0.5 * M_PI, core::Vec3::UnitX()));
    const double mass = 2.0;
    core::Model model = onFloor(box, mass, (mass * 0.04 / 6.0) * core::Mat3::Identity(), 0.25 - 0.03);
    model.bodies[1].orientation_WB = core::Quat(Eigen::AngleAxisd(0.3, core::Vec3::UnitZ()));
    for (const std::string& name : engineNames())
    {
        SCOPED_TRACE(name);
        const ContactRun run = runWithPenetration(model, name, 1000);
        const Pose& p = run.end[1];
        const core::Vec3 centre = p.position_W + p.orientation_WB * box.position_BS;
        EXPECT_NEAR(centre.z(), 0.15, 2e-3);
        EXPECT_LT(p.orientation_WB.angularDistance(model.bodies[1].orientation_WB),
                  0.05); // on the right face
        EXPECT_LT(run.deepest, name.rfind("mujoco", 0) == 0 ? 15e-3 : 5e-3);
        EXPECT_LT(PenetrationMeter(model).deepest(run.end), 2e-3);
    }
}

// A ball (radius 0.1 m, solid) thrown along x at 1 m/s without spin slides on the floor (mu = 0.5)
// until it rolls, at 5/7 of its speed, after 2 v0 / (7 mu g) = 0.06 s; at 0.3 s it rolls at
// 0.714 m/s. Without friction it would keep 1 m/s; a wrong radius would sink or lift it.
TEST(Peers, SlidingBallEndsRollingInEveryEngine)
{
    core::Shape ball;
    ball.type = core::ShapeType::Sphere;
    ball.radius = 0.1;
    const double mass = 1.0;
    core::Model model = onFloor(ball, mass, (0.4 * mass * 0.01) * core::Mat3::Identity(), 0.1);
    model.bodies[1].velocity_W = core::Vec3(1.0, 0.0, 0.0);
    for (const std::string& name : engineNames())
    {
        SCOPED_TRACE(name);
        const ContactRun run = runWithPenetration(model, name, 300);
        const core::Vec3 v = (run.end[1].position_W - run.before[1].position_W) / model.simulation.dt;
        EXPECT_NEAR(v.x(), 5.0 / 7.0, 0.03);
        EXPECT_NEAR(run.end[1].position_W.z(), 0.1, 2e-3);
        EXPECT_LT(run.deepest, 5e-3);
    }
}

} // namespace
} // namespace frontier::peers
