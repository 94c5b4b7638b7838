// app/check_command.cpp: `frontier check`: re-simulate a scene with the settings its reference
// trajectory was recorded with (the header line of the CSV) and compare, quantity by quantity.
#include "app/cli_options.h"
#include "app/commands.h"
#include "app/progress.h"
#include "core/impulse_solver.h"
#include "io/scene.h"
#include "io/trajectory.h"
#include "run/method.h"
#include "run/run_loop.h"
#include "run/scene_loading.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
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

// The reference and the scene it is checked against, fitted to each other.
struct CheckedReference
{
    io::Trajectory trajectory;
    core::Model model; // the scene with the reference's settings
    long steps = 0;
    int recordEvery = 1;
    std::vector<std::size_t> timeStart;   // per recorded time: index of its first row
    std::map<std::string, int> bodyIndex; // moving body name -> index in the model
};

// Moving body name -> index in the model.
std::map<std::string, int> movingBodyIndex(const core::Model& model)
{
    std::map<std::string, int> index;
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
    {
        if (!model.bodies[i].isStatic)
        {
            index[model.bodies[i].name] = static_cast<int>(i);
        }
    }
    return index;
}

// As many recorded times as the header's steps and record_every make. Throws io::InputError.
void checkRecordedTimes(const std::string& ref, const CheckedReference& out)
{
    const io::Trajectory& reference = out.trajectory;
    const std::size_t expected = static_cast<std::size_t>(out.steps / out.recordEvery) + 1;
    if (out.timeStart.size() != expected)
    {
        // The first time too many, or the last row when times are missing.
        const int line = out.timeStart.size() > expected ? reference.rows[out.timeStart[expected]].line
                                                         : reference.rows.back().line;
        throw io::InputError(ref, line, 0,
                             "the reference has " + std::to_string(out.timeStart.size()) +
                                 " recorded times, but " + std::to_string(out.steps) +
                                 " steps recorded every " + std::to_string(out.recordEvery) + " make " +
                                 std::to_string(expected) + " (missing or extra times)");
    }
}

// Indexes the reference's rows by time and checks they fit the scene: the same moving bodies at
// every recorded time, as many times as the header's steps and record_every make. Throws
// io::InputError.
void indexReferenceRows(const std::string& scene, const std::string& ref, CheckedReference& out)
{
    const io::Trajectory& reference = out.trajectory;
    std::set<std::string> sceneBodies;
    out.bodyIndex = movingBodyIndex(out.model);
    for (const auto& body : out.bodyIndex)
    {
        sceneBodies.insert(body.first);
    }
    std::set<std::string> atThisTime;
    // `line`: the first row of the time being closed.
    auto closeTime = [&](double time, int line)
    {
        for (const std::string& name : sceneBodies)
        {
            if (!atThisTime.count(name))
            {
                throw io::InputError(ref, line, 0,
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
                closeTime(reference.rows[r - 1].time, reference.rows[out.timeStart.back()].line);
            }
            out.timeStart.push_back(r);
            atThisTime.clear();
        }
        if (!sceneBodies.count(row.body))
        {
            throw io::InputError(ref, row.line, 0,
                                 "the reference has body '" + row.body + "', which is not a moving body of " +
                                     scene + " (a reference of another scene?)");
        }
        atThisTime.insert(row.body);
    }
    if (reference.rows.empty())
    {
        throw io::InputError(ref, 0, 0, "the reference has no rows");
    }
    closeTime(reference.rows.back().time, reference.rows[out.timeStart.back()].line);
    checkRecordedTimes(ref, out);
}

// Reads the reference, loads the scene as the reference's run did (its robot flags, then
// options.packagePaths first) with the reference's settings. Throws io::InputError.
CheckedReference loadReference(const CheckOptions& options)
{
    CheckedReference out;
    const std::string& ref = options.reference;
    out.trajectory = io::readTrajectory(ref);
    io::UrdfOptions urdf = io::urdfOptionsFrom(out.trajectory.metadata, ref);
    urdf.packagePaths.insert(urdf.packagePaths.begin(), options.packagePaths.begin(),
                             options.packagePaths.end());
    out.model = run::loadScene(options.scene, urdf).model;
    const io::TrajectorySettings header = io::readTrajectorySettings(out.trajectory, ref);
    out.model.simulation.dt = header.simulation.dt;
    run::Method::of(header.simulation).applyTo(out.model.simulation);
    header.contact.applyTo(out.model.contact);
    out.steps = header.steps;
    out.recordEvery = header.recordEvery;
    indexReferenceRows(options.scene, ref, out);
    return out;
}

// The expected and simulated values of quantity q (position, orientation, velocity, angular
// velocity) and how many of the four numbers count.
void quantityValues(int q, const core::BodyState& expected, const core::BodyState& got, Eigen::Vector4d& e,
                    Eigen::Vector4d& g, int& n)
{
    n = 3;
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
}

// Compares the simulated states with the reference at its recorded times: the largest error per
// quantity, the first one beyond its tolerance, and whether the times fit.
class Comparison
{
  public:
    Comparison(const CheckedReference& reference, const CheckOptions& options)
        : mReference(reference), mReferencePath(options.reference),
          mQuantities{{{"position", "m", options.positionTolerance, 0.0, 0.0, {}},
                       {"orientation", "rad", options.orientationTolerance, 0.0, 0.0, {}},
                       {"velocity", "m/s", options.velocityTolerance, 0.0, 0.0, {}},
                       {"angular velocity", "rad/s", options.angularVelocityTolerance, 0.0, 0.0, {}}}}
    {
    }

    void compare(const core::State& state)
    {
        const io::Trajectory& trajectory = mReference.trajectory;
        if (state.step % mReference.recordEvery != 0 || !misfit.empty())
        {
            return;
        }
        const std::size_t begin = mReference.timeStart[recorded];
        const std::size_t end = recorded + 1 < mReference.timeStart.size()
                                    ? mReference.timeStart[recorded + 1]
                                    : trajectory.rows.size();
        if (std::abs(trajectory.rows[begin].time - state.time) > 1e-9 * std::max(1.0, std::abs(state.time)))
        {
            misfit =
                io::InputError(mReferencePath, trajectory.rows[begin].line, 1,
                               "the reference's time " + std::to_string(trajectory.rows[begin].time) +
                                   " s does not match the simulated " + std::to_string(state.time) + " s")
                    .what();
            return;
        }
        ++recorded;
        for (std::size_t r = begin; r < end; ++r)
        {
            compareRow(trajectory.rows[r], state);
        }
    }

    const std::array<Quantity, 4>& quantities() const { return mQuantities; }

    std::string firstDivergence;
    std::size_t recorded = 0;
    std::string misfit; // "REF:LINE:COL: error: ..." when the reference's times do not fit the run

  private:
    void compareRow(const io::TrajectoryRow& row, const core::State& state)
    {
        const core::BodyState expected = row.state();
        const core::BodyState& got =
            state.bodies[static_cast<std::size_t>(mReference.bodyIndex.at(row.body))];
        const double errors[4] = {(got.position_W - expected.position_W).norm(),
                                  orientationError(got.orientation_WB, expected.orientation_WB),
                                  (got.velocity_W - expected.velocity_W).norm(),
                                  (got.angularVelocity_W - expected.angularVelocity_W).norm()};
        for (int q = 0; q < 4; ++q)
        {
            Quantity& quantity = mQuantities[static_cast<std::size_t>(q)];
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
                quantityValues(q, expected, got, e, g, n);
                char text[512];
                std::snprintf(
                    text, sizeof text,
                    "first divergence at t = %.9g s, body '%s', %s: expected %s, got %s, error %.3g %s "
                    "(tolerance %.3g %s)",
                    state.time, row.body.c_str(), quantity.name, formatVector(e, n).c_str(),
                    formatVector(g, n).c_str(), errors[q], quantity.unit, quantity.tolerance, quantity.unit);
                firstDivergence = text;
            }
        }
    }

    const CheckedReference& mReference;
    std::string mReferencePath; // for messages
    std::array<Quantity, 4> mQuantities;
};

// "checking  42%  t = 0.420 s" on a terminal, once per percent.
std::function<void(long)> checkProgress(bool terminal, long steps, double dt)
{
    auto lastShown = std::make_shared<long>(-1);
    return [=](long step)
    {
        const long percent = 100 * step / std::max(1L, steps);
        if (terminal && percent != *lastShown)
        {
            *lastShown = percent;
            std::fprintf(stderr, "\r\033[Kchecking %3ld%%  t = %.3f s", percent,
                         static_cast<double>(step) * dt);
        }
    };
}

// The largest error per quantity, then the verdict; the exit code.
int reportCheck(const CheckOptions& options, const Comparison& comparison, const run::RunSummary& summary)
{
    for (const Quantity& q : comparison.quantities())
    {
        std::printf("largest %s error %.3g %s (tolerance %.3g %s)%s%s\n", q.name, q.largest, q.unit,
                    q.tolerance, q.unit, q.largestBody.empty() ? "" : ", body ", q.largestBody.c_str());
    }
    if (!summary.completed)
    {
        std::printf("FAILED: %s\n", summary.failure.c_str());
        return cExitFailed;
    }
    if (!comparison.firstDivergence.empty())
    {
        std::printf("FAILED: %s\n", comparison.firstDivergence.c_str());
        return cExitFailed;
    }
    std::printf("OK: %s matches %s (%zu recorded times)\n", options.scene.c_str(), options.reference.c_str(),
                comparison.recorded);
    return cExitOk;
}
} // namespace

int checkCommand(const CheckOptions& options)
{
    CheckedReference reference;
    try
    {
        reference = loadReference(options);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }

    Comparison comparison(reference, options);
    const run::Recorder compare = [&](const core::State& state, const core::Simulator*)
    { comparison.compare(state); };
    run::RunSettings settings;
    settings.steps = reference.steps;
    const bool terminal = !options.quiet && stderrIsTerminal();
    settings.progress = checkProgress(terminal, reference.steps, reference.model.simulation.dt);
    run::RunSummary summary;
    run::installInterruptHandlers();
    try
    {
        summary = run::runSimulation(reference.model, settings, compare);
    }
    catch (const core::SingularJointError& e) // singular at the start: the run fails, as in `run`
    {
        summary.completed = false;
        summary.failure = e.what();
    }
    catch (const std::exception& e)
    {
        std::cerr << "frontier: " << options.scene << ": " << e.what() << "\n";
        return cExitBadInput;
    }
    if (summary.interruptedBy != 0)
    {
        if (terminal)
        {
            std::fprintf(stderr, "\r\033[K");
        }
        std::cerr << "frontier: " << summary.failure << "; the check did not finish\n";
        return run::interruptedExitCode(summary.interruptedBy);
    }
    if (terminal)
    {
        std::fprintf(stderr, "\r\033[K");
    }
    if (!comparison.misfit.empty())
    {
        std::cerr << "frontier: " << comparison.misfit << "\n";
        return cExitBadInput;
    }
    return reportCheck(options, comparison, summary);
}

namespace
{
void addCheckOptions(CLI::App& command, CheckOptions& o)
{

    command.add_option("scene", o.scene, cSceneFiles)->required();
    command.add_option("--reference", o.reference, "reference trajectory CSV")->required();
    command.add_option("--tol", o.positionTolerance, "position tolerance (m)")->check(cTolerance);
    command.add_option("--tol-orientation", o.orientationTolerance, "orientation tolerance (rad)")
        ->check(cTolerance);
    command.add_option("--tol-velocity", o.velocityTolerance, "velocity tolerance (m/s)")->check(cTolerance);
    command
        .add_option("--tol-angular-velocity", o.angularVelocityTolerance,
                    "angular velocity tolerance (rad/s)")
        ->check(cTolerance);
    command.add_flag("--quiet", o.quiet, "no progress line");
    addPackagePathOption(command, o.packagePaths);
}
} // namespace

Command addCheckCommand(CLI::App& app)
{
    return addCommand<CheckOptions>(app, "check",
                                    "re-simulate a scene and compare with a recorded reference trajectory",
                                    addCheckOptions, checkCommand);
}

} // namespace frontier::app
