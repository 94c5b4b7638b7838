// tests/contact/materials_test.cpp: friction and restitution per body, mixed per pair as
// core::contactFriction and core::contactRestitution say (sqrt(mu_a mu_b), max(e_a, e_b)), and
// the physics that follows from the pair's values.
#include "contact_harness.h"

#include <cmath>
#include <gtest/gtest.h>
#include <string>

namespace frontier::test
{
namespace
{

TEST(Materials, PairValuesMixAsDocumented)
{
    core::Model model;
    model.contact.friction = 0.8;
    model.contact.restitution = 0.1;
    model.bodies.resize(3);
    model.bodies[0].friction = 0.2;
    model.bodies[0].restitution = 0.6;
    model.bodies[1].friction = 0.45;
    EXPECT_DOUBLE_EQ(core::contactFriction(model, 0, 1), std::sqrt(0.2 * 0.45));
    EXPECT_DOUBLE_EQ(core::contactFriction(model, 0, 2), std::sqrt(0.2 * 0.8)); // body 2: the scene's
    EXPECT_DOUBLE_EQ(core::contactFriction(model, 0, core::cWorld), std::sqrt(0.2 * 0.8));
    EXPECT_EQ(core::contactFriction(model, 2, core::cWorld), 0.8); // no material: the scene's exactly
    EXPECT_EQ(core::contactRestitution(model, 0, 2), 0.6);
    EXPECT_EQ(core::contactRestitution(model, 1, 2), 0.1);
}

// A ball of restitution 0.8 dropped on a floor in a scene whose restitution is 0: the pair's is the
// larger, 0.8, so the first bounce rises to 0.8^2 of the drop (1 m) within 2%; without the ball's
// own value it does not bounce at all.
double firstBounce(const std::string& ballMaterial)
{
    const std::string yaml =
        "simulation: {dt: 0.001, duration: 2, gravity: [0, 0, -9.81]}\n"
        "contact: {friction: 0.5, restitution: 0.0}\n"
        "bodies:\n"
        "  - {name: floor, static: true, shape: {type: plane, normal: [0, 0, 1], offset: 0}}\n"
        "  - {name: ball, shape: {type: sphere, radius: 0.1}, mass: 0.5, position: [0, 0, 1.1]" +
        ballMaterial + "}\n";
    SceneRun run(io::loadSceneFromString(yaml, "ball.yaml"));
    bool bounced = false;
    double apex = 0.0; // m, of the lowest point after the first bounce
    for (long k = 0; k < run.stepsFor(2.0); ++k)
    {
        run.step();
        const core::BodyState& ball = run.body("ball");
        bounced = bounced || ball.velocity_W.z() > 0.0;
        if (bounced)
        {
            apex = std::max(apex, ball.position_W.z() - 0.1);
        }
    }
    return apex;
}

TEST(Materials, ABodysRestitutionBouncesItOnAFloorOfNone)
{
    EXPECT_NEAR(firstBounce(", restitution: 0.8"), 0.64, 0.02 * 0.64);
    EXPECT_LT(firstBounce(""), 1e-3);
}

// A 10 cm box on a 30 degree incline (tan 30 = 0.577) in a scene whose friction is 0.3: with its
// own friction 1.2 the pair's is sqrt(0.3 x 1.2) = 0.6 and it sticks (under 1 mm in 1 s); with 0.5
// on the box and 0.5 on the ramp the pair's is 0.5 and it slides with g (sin - 0.5 cos) within 1%.
struct Slide
{
    double moved = 0.0;        // m in 1 s
    double acceleration = 0.0; // m/s^2 down the slope, from the distance between 0.5 s and 1 s
};

Slide slideDown(const std::string& rampMaterial, const std::string& boxMaterial)
{
    const double a = 30.0 * 3.14159265358979323846 / 180.0;
    char yaml[1024];
    std::snprintf(
        yaml, sizeof yaml,
        "simulation: {dt: 0.001, duration: 1, gravity: [0, 0, -9.81]}\n"
        "contact: {friction: 0.3, restitution: 0.0}\n"
        "bodies:\n"
        "  - {name: ramp, static: true, shape: {type: plane, normal: [%.17g, 0, %.17g], offset: 0}%s}\n"
        "  - {name: box, shape: {type: box, size: [0.1, 0.1, 0.1]}, mass: 1.0, position: [%.17g, 0, "
        "%.17g], orientation: [%.17g, 0, %.17g, 0]%s}\n",
        -std::sin(a), std::cos(a), rampMaterial.c_str(), std::cos(a) - 0.05 * std::sin(a),
        std::sin(a) + 0.05 * std::cos(a), std::cos(a / 2), -std::sin(a / 2), boxMaterial.c_str());
    SceneRun run(io::loadSceneFromString(yaml, "incline.yaml"));
    const Vec3 down(-std::cos(a), 0.0, -std::sin(a));
    const Vec3 start = run.body("box").position_W;
    double atHalf = 0.0, speedAtHalf = 0.0;
    Slide out;
    for (long k = 1; k <= run.stepsFor(1.0); ++k)
    {
        run.step();
        if (k == run.stepsFor(0.5))
        {
            atHalf = down.dot(run.body("box").position_W - start);
            speedAtHalf = down.dot(run.body("box").velocity_W);
        }
    }
    out.moved = (run.body("box").position_W - start).norm();
    const double atEnd = down.dot(run.body("box").position_W - start);
    out.acceleration = 2.0 * (atEnd - atHalf - 0.5 * speedAtHalf) / (0.5 * 0.5); // s = v t + a t^2 / 2
    return out;
}

TEST(Materials, FrictionOfAPairIsTheGeometricMeanOfTheBodies)
{
    const double a = 30.0 * 3.14159265358979323846 / 180.0;
    EXPECT_GT(slideDown("", "").moved, 0.1); // the scene's 0.3 alone: it slides
    EXPECT_LT(slideDown("", ", friction: 1.2").moved, 1e-3);
    const Slide slide = slideDown(", friction: 0.5", ", friction: 0.5");
    const double expected = 9.81 * (std::sin(a) - 0.5 * std::cos(a));
    EXPECT_NEAR(slide.acceleration, expected, 0.01 * expected);
}

TEST(Materials, BadBodyValuesAreErrorsAtTheirLine)
{
    const std::string yaml =
        "bodies:\n  - {name: b, shape: {type: sphere, radius: 0.1}, mass: 1, restitution: 2}\n";
    try
    {
        io::loadSceneFromString(yaml, "bad.yaml");
        FAIL();
    }
    catch (const io::InputError& e)
    {
        EXPECT_EQ(e.line(), 2);
        EXPECT_NE(std::string(e.what()).find("expected a number in [0, 1] for 'restitution'"),
                  std::string::npos)
            << e.what();
    }
}

} // namespace
} // namespace frontier::test
