// app/cli_options.cpp: the shared option rules and groups of app/cli_options.h.
#include "app/cli_options.h"

#include "app/model_overrides.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace frontier::app
{

CLI::Validator numberIn(double low, double high, bool positive, bool count, const char* name)
{
    return CLI::Validator(
        [=](std::string& value)
        {
            char* end = nullptr;
            const double x = std::strtod(value.c_str(), &end);
            const bool parsed = !value.empty() && end == value.c_str() + value.size();
            if (!parsed || !std::isfinite(x))
            {
                return "expected a finite number, got '" + value + "'";
            }
            char range[96];
            std::snprintf(range, sizeof range,
                          count ? "%s %s %.0f and at most %.0f" : "%s %s %.6g and at most %.6g",
                          count ? "a whole number" : "a number", positive ? "above" : "from", low, high);
            if (x < low || (positive && x == low) || x > high || (count && x != std::floor(x)))
            {
                return std::string("expected ") + range + ", got " + value;
            }
            if (count)
            {
                value = std::to_string(static_cast<long long>(x));
            }
            return std::string();
        },
        name != nullptr ? name : (count ? "INTEGER" : "NUMBER"));
}

const CLI::Validator cTimeStep = numberIn(0.0, cMaxTimeStepS, true, false); // s
const CLI::Validator cDuration = numberIn(0.0, cMaxDurationS, true, false); // s
const CLI::Validator cStepCount = numberIn(1.0, 1e12, false, true);     // steps (run/run_loop.h cMaxSteps)
const CLI::Validator cIterations = numberIn(1.0, 1e6, false, true);     // solver sweeps
const CLI::Validator cEvery = numberIn(1.0, 2147483647.0, false, true); // steps between rows
const CLI::Validator cFps = numberIn(0.0, 1e6, true, false);            // frames per simulated second
const CLI::Validator cPixels = numberIn(16.0, 16384.0, false, true, "PIXELS"); // frame width
const CLI::Validator cJobs = numberIn(1.0, 256.0, false, true);
const CLI::Validator cTolerance = numberIn(0.0, 1e12, true, false);    // m, rad, m/s, rad/s
const CLI::Validator cDropHeight = numberIn(0.0, 1e6, false, false);   // m
const CLI::Validator cRows = numberIn(1.0, 2147483647.0, false, true); // KKT rows

const CLI::Validator cPath([](std::string& value)
                           { return value.empty() ? std::string("expected a path, got ''") : std::string(); },
                           "PATH");

const CLI::Validator cFrameHeight(
    [](std::string& value)
    {
        int pixels = 0;
        const bool whole = CLI::detail::lexical_cast(value, pixels);
        if (whole && pixels >= 16 && pixels <= 16384 && cPixels(value).empty())
        {
            return std::string();
        }
        return "--height is the frame height in pixels (16 to 16384), got " + value +
               "; to start a robot higher above the floor, use --drop-height METRES";
    },
    "PIXELS");

void addPackagePathOption(CLI::App& command, std::vector<std::string>& packagePaths)
{
    command
        .add_option("--package-path", packagePaths,
                    "where package://NAME/ meshes are: a package, a folder of packages, or NAME=DIR "
                    "(repeatable; searched before ROS_PACKAGE_PATH)")
        ->allow_extra_args(false);
}

namespace
{
// NAME=VALUE with a name and a finite number.
CLI::Validator jointPositionEntry()
{
    return CLI::Validator(
        [](std::string& entry)
        {
            const std::size_t equals = entry.rfind('=');
            if (equals == std::string::npos || equals == 0)
            {
                return "expected NAME=POSITION (a joint of the URDF and rad or m), got " + entry;
            }
            const std::string value = entry.substr(equals + 1);
            char* end = nullptr;
            const double position = std::strtod(value.c_str(), &end);
            return !value.empty() && *end == '\0' && std::isfinite(position)
                       ? std::string()
                       : "expected a finite number after '=' in " + entry;
        },
        "NAME=POSITION");
}

} // namespace

void addRobotOptions(CLI::App& command, io::UrdfOptions& o)
{
    addPackagePathOption(command, o.packagePaths);
    auto* fixed = command.add_flag("--fixed-base", o.fixedBase, "weld a bare URDF's root link to the world");
    command
        .add_flag("--free-base", o.freeBase, "let a bare URDF's root float even if it is welded to 'world'")
        ->excludes(fixed);
    command
        .add_option(
            "--drop-height", o.dropHeight,
            "a free-floating bare URDF starts with its lowest collision point this high above the floor (m)")
        ->check(cDropHeight);
    command
        .add_option_function<std::vector<std::string>>(
            "--joint-position",
            [&o](const std::vector<std::string>& entries)
            {
                for (const std::string& entry : entries)
                {
                    const std::size_t equals = entry.rfind('=');
                    o.jointPositions[entry.substr(0, equals)] =
                        std::strtod(entry.c_str() + equals + 1, nullptr);
                }
            },
            "a bare URDF's joint starts at this position (rad or m, the URDF's convention), within its "
            "limits; --hold holds it there (repeatable)")
        ->check(jointPositionEntry())
        ->allow_extra_args(false);
    command
        .add_option_function<std::string>(
            "--self-collision", [&o](const std::string& value) { o.selfCollision = value == "on"; },
            "on: links collide unless joined or overlapping at the start (default); off: never")
        ->check(CLI::IsMember({"on", "off"}));
    command.add_option("--keyframe", o.keyframe,
                       "a bare MJCF file starts in this <key> of it (its qpos, qvel and ctrl)");
    command.add_flag("--hold", o.hold,
                     "a position servo on every joint of every URDF robot, holding it where it starts "
                     "(gains from the joint's inertia and effort limit)");
}

void addContactToleranceOptions(CLI::App& command, core::ContactTolerances& o, const std::string& which)
{
    // Core's rule on a value numberIn (checked first) found to be a finite number.
    const auto inRange = [](bool (*rule)(double), const char* expected)
    {
        return CLI::Validator(
            [rule, expected](std::string& value)
            {
                return rule(std::strtod(value.c_str(), nullptr))
                           ? std::string()
                           : std::string("expected ") + expected + ", got " + value;
            },
            "");
    };
    command
        .add_option("--contact-tolerance", o.tolerance,
                    "velocity (m/s) to which each contact, limit and loop row is solved " + which +
                        " (default: the scene's contact.tolerance, else 3e-5); larger is faster and "
                        "lets bodies sink and creep more")
        ->check(numberIn(0.0, core::cMaxContactTolerance, false, false))
        ->check(inRange(core::isContactTolerance, core::cContactToleranceRange));
    command
        .add_option("--contact-relative-tolerance", o.relativeTolerance,
                    "fraction of a contact island's starting residual to which it is solved " + which +
                        ", if larger than --contact-tolerance (default: the scene's "
                        "contact.relative_tolerance, else 0)")
        ->check(numberIn(0.0, 1.0, false, false))
        ->check(inRange(core::isRelativeContactTolerance, core::cRelativeContactToleranceRange));
}

} // namespace frontier::app
