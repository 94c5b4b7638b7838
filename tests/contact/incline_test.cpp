// tests/contact/incline_test.cpp: a box on an inclined plane (scenes/box_incline.yaml,
// scenes/box_incline_slide.yaml, and other angles and friction coefficients built as YAML text).
// Coulomb friction: the box sticks when tan(angle) < mu, otherwise it slides down with the
// constant acceleration g (sin - mu cos).
#include "contact_harness.h"

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>

namespace frontier::test
{
namespace
{

constexpr double cPi = 3.14159265358979323846;
constexpr double cG = 9.81;

// The scene of scenes/box_incline.yaml for any angle (degrees) and mu: a plane through the origin
// tilted about y, rising towards +x, and a 10 cm, 1 kg box lying flat on it 1 m up the slope.
std::string inclineYaml(double angleDeg, double mu)
{
    const double a = angleDeg * cPi / 180.0;
    const double s0 = 1.0;
    std::ostringstream y;
    y.precision(17);
    y << "name: incline\n"
      << "simulation: {dt: 0.001, duration: 2.0, gravity: [0, 0, -9.81], solver: linear}\n"
      << "contact: {friction: " << mu << ", restitution: 0.0}\n"
      << "bodies:\n"
      << "  - name: ramp\n    static: true\n"
      << "    shape: {type: plane, normal: [" << -std::sin(a) << ", 0, " << std::cos(a) << "], offset: 0}\n"
      << "  - name: box\n    shape: {type: box, size: [0.1, 0.1, 0.1]}\n    mass: 1.0\n"
      << "    position: [" << s0 * std::cos(a) - 0.05 * std::sin(a) << ", 0, "
      << s0 * std::sin(a) + 0.05 * std::cos(a) << "]\n"
      << "    orientation: [" << std::cos(a / 2) << ", 0, " << -std::sin(a / 2) << ", 0]\n";
    return y.str();
}

struct InclineRun
{
    double angle = 0.0;              // rad, from the plane normal
    double maxMove = 0.0;            // largest distance of the box from its start (m)
    double fittedAcceleration = 0.0; // down the slope (m/s^2), from s(t) = s0 + v0 t + a t^2 / 2
    double fitResidual = 0.0;        // largest |s - fit| (m)
    double maxLift = 0.0;            // largest height of the box centre above its resting height (m)
};

// Runs the box for `seconds` and fits its distance down the slope after `settle` seconds.
InclineRun runIncline(core::Model model, double seconds, double settle)
{
    SceneRun run(std::move(model));
    const core::Body& rampBody = run.model.bodies[static_cast<std::size_t>(run.model.findBody("ramp"))];
    const Vec3 n = rampBody.shapes[0].normal;
    InclineRun out;
    out.angle = std::acos(n.z());
    // Down the slope: gravity's part in the plane.
    const Vec3 g(0, 0, -1);
    const Vec3 down = (g - g.dot(n) * n).normalized();
    const Vec3 start = run.body("box").position_W;
    const double startHeight = n.dot(start);
    std::vector<double> t, s;
    const long steps = run.stepsFor(seconds);
    for (long k = 0; k < steps; ++k)
    {
        run.step();
        const core::BodyState& box = run.body("box");
        EXPECT_TRUE(box.position_W.allFinite());
        out.maxMove = std::max(out.maxMove, (box.position_W - start).norm());
        out.maxLift = std::max(out.maxLift, std::abs(n.dot(box.position_W) - startHeight));
        if (run.state.time > settle)
        {
            t.push_back(run.state.time);
            s.push_back(down.dot(box.position_W - start));
        }
    }
    Eigen::MatrixXd A(static_cast<Eigen::Index>(t.size()), 3);
    Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
    for (std::size_t k = 0; k < t.size(); ++k)
    {
        const auto r = static_cast<Eigen::Index>(k);
        A(r, 0) = 1.0;
        A(r, 1) = t[k];
        A(r, 2) = 0.5 * t[k] * t[k];
        b(r) = s[k];
    }
    const Eigen::Vector3d c = A.colPivHouseholderQr().solve(b);
    out.fittedAcceleration = c(2);
    out.fitResidual = (A * c - b).cwiseAbs().maxCoeff();
    return out;
}

// tan(20 deg) = 0.364 < mu = 0.5: static friction holds the box. Bound: under 1 mm in 2 s
// (it creeps by about 2e-6 m: the contact rows are solved to 3e-5 m/s each step, core/extra_rows.h).
TEST(Incline, BoxSticksWhenTanAngleBelowMu)
{
    core::Model model = io::loadScene(scenePath("box_incline.yaml"));
    ASSERT_LT(std::tan(20.0 * cPi / 180.0), model.contact.friction);
    const InclineRun r = runIncline(std::move(model), 2.0, 0.1);
    std::printf("20 deg, mu 0.5: moved %.3g m in 2 s\n", r.maxMove);
    EXPECT_LT(r.maxMove, 1e-3);
}

// tan(30 deg) = 0.577 > mu = 0.3: the box slides with g (sin - mu cos) = 2.3563 m/s^2. The
// fit starts after 0.1 s of settling; bound 1% of the expected acceleration.
// Measured with the contact solve of this writing: 2.518 m/s^2 (friction 6.4% short). The
// cone projection in solveExtraRows (core/extra_rows_solve.cpp) scales the step by the inverse of
// each contact's anisotropic 2x2 tangential Delassus block, then projects radially, so a
// sliding corner's friction is not opposite to its slip; with an isotropic step before the
// radial projection the fit matches to 1e-12.
TEST(Incline, BoxSlidesWithCoulombAcceleration)
{
    core::Model model = io::loadScene(scenePath("box_incline_slide.yaml"));
    const double mu = model.contact.friction;
    const InclineRun r = runIncline(std::move(model), 2.0, 0.1);
    const double expected = cG * (std::sin(r.angle) - mu * std::cos(r.angle));
    std::printf("30 deg, mu 0.3: a = %.6f m/s^2, expected %.6f (fit residual %.2g m)\n", r.fittedAcceleration,
                expected, r.fitResidual);
    EXPECT_NEAR(r.angle, 30.0 * cPi / 180.0, 1e-9);
    EXPECT_NEAR(r.fittedAcceleration, expected, 0.01 * expected);
    // The motion is uniformly accelerated: the quadratic fits to 0.1 mm.
    EXPECT_LT(r.fitResidual, 1e-4);
    // It slides flat: its centre stays at its resting height over the plane to 0.1 mm.
    EXPECT_LT(r.maxLift, 1e-4);
}

// More angles and coefficients, from YAML text. Each either sticks (under 1 mm in 2 s) or slides
// with g (sin - mu cos) within 1%.
struct IncCase
{
    double angleDeg, mu;
};

class InclineSweep : public ::testing::TestWithParam<IncCase>
{
};

TEST_P(InclineSweep, SticksOrSlidesByCoulomb)
{
    const IncCase c = GetParam();
    const double a = c.angleDeg * cPi / 180.0;
    const InclineRun r =
        runIncline(io::loadSceneFromString(inclineYaml(c.angleDeg, c.mu), "incline.yaml"), 2.0, 0.1);
    EXPECT_NEAR(r.angle, a, 1e-9);
    if (std::tan(a) < c.mu)
    {
        std::printf("%g deg, mu %g (tan %.3f): sticks, moved %.3g m\n", c.angleDeg, c.mu, std::tan(a),
                    r.maxMove);
        EXPECT_LT(r.maxMove, 1e-3);
    }
    else
    {
        const double expected = cG * (std::sin(a) - c.mu * std::cos(a));
        std::printf("%g deg, mu %g (tan %.3f): a = %.6f, expected %.6f, rel. error %.2g\n", c.angleDeg, c.mu,
                    std::tan(a), r.fittedAcceleration, expected, r.fittedAcceleration / expected - 1.0);
        EXPECT_NEAR(r.fittedAcceleration, expected, 0.01 * expected);
        EXPECT_LT(r.maxLift, 1e-4);
    }
}

INSTANTIATE_TEST_SUITE_P(AnglesAndCoefficients, InclineSweep,
                         ::testing::Values(IncCase{10.0, 0.2}, IncCase{25.0, 0.5}, IncCase{40.0, 0.9},
                                           IncCase{20.0, 0.35}, IncCase{35.0, 0.5}, IncCase{45.0, 0.2},
                                           IncCase{20.0, 0.0}),
                         [](const ::testing::TestParamInfo<IncCase>& param)
                         {
                             return "deg" + std::to_string(static_cast<int>(param.param.angleDeg)) + "_mu" +
                                    std::to_string(static_cast<int>(std::lround(100 * param.param.mu)));
                         });

} // namespace
} // namespace frontier::test
