// app/check_command.cpp: `frontier check`: re-simulate a scene with the settings its reference
// trajectory was recorded with (the header line of the CSV) and compare, quantity by quantity.
#include "app/commands.h"
#include "app/method.h"
#include "app/progress.h"
#include "app/run_loop.h"
#include "app/scene_loading.h"
#include "io/scene.h"
#include "io/trajectory.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <set>

namespace frontier::app
{

namespace
{
struct Quantity
{
    const char* name;
    const char* unit;
    double tolerance;
    double largest = 0.0;
    double largestTime = 0.0;
    std::string largestBody;
};

// Angle of the rotation between two orientations (rad), accurate near zero (no acos of ~1).
double orientationError(const core::Quat& a, const core::Quat& b)
{
    const core::Quat d = a.normalized().conjugate() * b.normalized();
    return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

std::string formatVector(const Eigen::Vector4d& v, int n)
{
    char text[160];
    if (n == 4)
    {
        std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g, %.9g)", v(0), v(1), v(2), v(3));
    }
    else
    {
        std::snprintf(text, sizeof text, "(%.9g, %.9g, %.9g)", v(0), v(1), v(2));
    }
    return text;
}
} // namespace

int checkCommand(const CheckOptions& options)
{
    io::Trajectory reference;
    core::Model model;
    long steps = 0;
    int recordEvery = 1;
    // Reference rows by time: index of the first row of each recorded time.
    std::vector<std::size_t> timeStart;
    std::map<std::string, int> bodyIndex;
    try
    {
        reference = io::readTrajectory(options.reference);
        io::UrdfOptions urdf = io::urdfOptionsFrom(reference.metadata, options.reference);
        urdf.packagePaths.insert(urdf.packagePaths.begin(), options.packagePaths.begin(),
                                 options.packagePaths.end());
        model = loadSceneWithRobots(options.scene, urdf).model;
        const std::string& ref = options.reference;
        const io::TrajectorySettings header = io::readTrajectorySettings(reference, ref);
        model.simulation.dt = header.simulation.dt;
        Method::of(header.simulation).applyTo(model.simulation);
        steps = header.steps;
        recordEvery = header.recordEvery;

        // The reference must fit the scene: the same moving bodies at every recorded time.
        std::set<std::string> sceneBodies;
        for (std::size_t i = 0; i < model.bodies.size(); ++i)
        {
            if (!model.bodies[i].isStatic)
            {
                bodyIndex[model.bodies[i].name] = static_cast<int>(i);
                sceneBodies.insert(model.bodies[i].name);
            }
        }
        std::set<std::string> atThisTime;
        auto closeTime = [&](double time)
        {
            for (const std::string& name : sceneBodies)
            {
                if (!atThisTime.count(name))
                {
                    throw io::InputError(ref, 0, 0,
                                         "body '" + name +
                                             "' of the scene is missing from the reference at t = " +
                                             std::to_string(time) + " s (a reference of another scene?)");
                }
            }
        };
        for (std::size_t r = 0; r < reference.rows.size(); ++r)
        {
            const io::TrajectoryRow& row = reference.rows[r];
            if (r == 0 || row.time != reference.rows[r - 1].time)
            {
                if (r > 0)
                {
                    closeTime(reference.rows[r - 1].time);
                }
                timeStart.push_back(r);
                atThisTime.clear();
            }
            if (!sceneBodies.count(row.body))
            {
                throw io::InputError(ref, 0, 0,
                                     "the reference has body '" + row.body +
                                         "', which is not a moving body of " + options.scene +
                                         " (a reference of another scene?)");
            }
            atThisTime.insert(row.body);
        }
        if (reference.rows.empty())
        {
            throw io::InputError(ref, 0, 0, "the reference has no rows");
        }
        closeTime(reference.rows.back().time);
        const std::size_t expected = static_cast<std::size_t>(steps / recordEvery) + 1;
        if (timeStart.size() != expected)
        {
            throw io::InputError(ref, 0, 0,
                                 "the reference has " + std::to_string(timeStart.size()) +
                                     " recorded times, but " + std::to_string(steps) +
                                     " steps recorded every " + std::to_string(recordEvery) + " make " +
                                     std::to_string(expected) + " (missing or extra times)");
        }
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }

    Quantity quantities[4] = {{"position", "m", options.positionTolerance, 0.0, 0.0, {}},
                              {"orientation", "rad", options.orientationTolerance, 0.0, 0.0, {}},
                              {"velocity", "m/s", options.velocityTolerance, 0.0, 0.0, {}},
                              {"angular velocity", "rad/s", options.angularVelocityTolerance, 0.0, 0.0, {}}};
    std::string firstDivergence;
    std::size_t recorded = 0;
    std::string misfit;
    const Recorder compare = [&](const core::State& state, const core::Simulator*)
    {
        if (state.step % recordEvery != 0 || !misfit.empty())
        {
            return;
        }
        const std::size_t begin = timeStart[recorded];
        const std::size_t end =
            recorded + 1 < timeStart.size() ? timeStart[recorded + 1] : reference.rows.size();
        if (std::abs(reference.rows[begin].time - state.time) > 1e-9 * std::max(1.0, std::abs(state.time)))
        {
            misfit = "the reference's time " + std::to_string(reference.rows[begin].time) +
                     " s does not match the simulated " + std::to_string(state.time) + " s";
            return;
        }
        ++recorded;
        for (std::size_t r = begin; r < end; ++r)
        {
            const io::TrajectoryRow& row = reference.rows[r];
            const core::BodyState expected = row.state();
            const core::BodyState& got = state.bodies[static_cast<std::size_t>(bodyIndex[row.body])];
            const double errors[4] = {(got.position_W - expected.position_W).norm(),
                                      orientationError(got.orientation_WB, expected.orientation_WB),
                                      (got.velocity_W - expected.velocity_W).norm(),
                                      (got.angularVelocity_W - expected.angularVelocity_W).norm()};
            for (int q = 0; q < 4; ++q)
            {
                Quantity& quantity = quantities[q];
                if (errors[q] > quantity.largest)
                {
                    quantity.largest = errors[q];
                    quantity.largestTime = state.time;
                    quantity.largestBody = row.body;
                }
                if (firstDivergence.empty() && !(errors[q] <= quantity.tolerance))
                {
                    Eigen::Vector4d e, g;
                    int n = 3;
                    if (q == 0)
                    {
                        e << expected.position_W, 0;
                        g << got.position_W, 0;
                    }
                    else if (q == 1)
                    {
                        n = 4;
                        e << expected.orientation_WB.w(), expected.orientation_WB.vec();
                        g << got.orientation_WB.w(), got.orientation_WB.vec();
                    }
                    else if (q == 2)
                    {
                        e << expected.velocity_W, 0;
                        g << got.velocity_W, 0;
                    }
                    else
                    {
                        e << expected.angularVelocity_W, 0;
                        g << got.angularVelocity_W, 0;
                    }
                    char text[512];
                    std::snprintf(
                        text, sizeof text,
                        "first divergence at t = %.9g s, body '%s', %s: expected %s, got %s, error %.3g %s "
                        "(tolerance %.3g %s)",
                        state.time, row.body.c_str(), quantity.name, formatVector(e, n).c_str(),
                        formatVector(g, n).c_str(), errors[q], quantity.unit, quantity.tolerance,
                        quantity.unit);
                    firstDivergence = text;
                }
            }
        }
    };
    RunSettings settings;
    settings.steps = steps;
    const bool terminal = !options.quiet && stderrIsTerminal();
    long lastShown = -1;
    settings.progress = [&](long step)
    {
        const long percent = 100 * step / std::max(1L, steps);
        if (terminal && percent != lastShown)
        {
            lastShown = percent;
            std::fprintf(stderr, "\r\033[Kchecking %3ld%%  t = %.3f s", percent,
                         static_cast<double>(step) * model.simulation.dt);
        }
    };
    RunSummary summary;
    try
    {
        summary = runSimulation(model, settings, compare);
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier: " << options.scene << ": " << e.what() << "\n";
        return cExitBadInput;
    }
    if (terminal)
    {
        std::fprintf(stderr, "\r\033[K");
    }
    if (!misfit.empty())
    {
        std::cerr << "frontier: " << options.reference << ": " << misfit << "\n";
        return cExitBadInput;
    }
    for (const Quantity& q : quantities)
    {
        std::printf("largest %s error %.3g %s (tolerance %.3g %s)%s%s\n", q.name, q.largest, q.unit,
                    q.tolerance, q.unit, q.largestBody.empty() ? "" : ", body ", q.largestBody.c_str());
    }
    if (!summary.finite)
    {
        std::printf("FAILED: %s\n", summary.failure.c_str());
        return cExitFailed;
    }
    if (!firstDivergence.empty())
    {
        std::printf("FAILED: %s\n", firstDivergence.c_str());
        return cExitFailed;
    }
    std::printf("OK: %s matches %s (%zu recorded times)\n", options.scene.c_str(), options.reference.c_str(),
                recorded);
    return cExitOk;
}

} // namespace frontier::app
