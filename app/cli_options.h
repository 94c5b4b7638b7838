// app/cli_options.h: the rules and option groups the commands share on the command line (CLI11):
// number ranges, paths, frame height, robot flags, contact tolerances. Each command registers its
// own options next to it (app/*_command.cpp), from these.
#pragma once

#include "app/commands.h"
#include "core/model.h"
#include "io/scene.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace frontier::app
{

// The one rule of every numeric flag: a finite number (no nan, no inf) in its range; a count is a
// whole number, rewritten in digits ("1e3" -> "1000") for the option's integer type. `positive`:
// the range excludes its lower end `low`.
CLI::Validator numberIn(double low, double high, bool positive, bool count, const char* name = nullptr);

// Ranges (README "Commands"): times in seconds, counts bounded where a larger one could only be a
// typo (a run's step count is bounded again from --duration / --dt, run/run_loop.h).
extern const CLI::Validator cTimeStep;   // s
extern const CLI::Validator cDuration;   // s
extern const CLI::Validator cStepCount;  // steps (run/run_loop.h cMaxSteps)
extern const CLI::Validator cIterations; // solver sweeps
extern const CLI::Validator cEvery;      // steps between rows
extern const CLI::Validator cFps;        // frames per simulated second
extern const CLI::Validator cPixels;     // frame width
extern const CLI::Validator cJobs;
extern const CLI::Validator cTolerance; // m, rad, m/s, rad/s
extern const CLI::Validator cRows;      // KKT rows

// An output path given as '' would silently write nothing.
extern const CLI::Validator cPath;

// --height is the frame height; a robot's start height is --drop-height (the names of both are kept
// from the command-line contract), so a height in metres gets pointed there.
extern const CLI::Validator cFrameHeight;

// What the scene arguments take (io::loadScene).
inline constexpr const char* cSceneFiles = "scene .yaml, model .urdf, MJCF .xml, or SDF .sdf/.world/.model";

// A flag's help for a choice among the names of core's table (core::solvers(), core::integrators()):
// "a | b | c (a: what it is; b: ...)".
template <class Info> std::string choiceHelp(std::span<const Info> table)
{
    std::string names;
    std::string descriptions;
    for (const Info& info : table)
    {
        names += (names.empty() ? "" : " | ") + std::string(info.name);
        descriptions += (descriptions.empty() ? "" : "; ") + std::string(info.name) + ": " + info.description;
    }
    return names + " (" + descriptions + ")";
}

// --package-path: where package://NAME/ meshes are.
void addPackagePathOption(CLI::App& command, std::vector<std::string>& packagePaths);

// Robot flags (README "Robots"): how a .urdf is read and placed.
void addRobotOptions(CLI::App& command, io::UrdfOptions& o);

// --contact-tolerance and --contact-relative-tolerance: when the contact solve stops (docs/method.md
// §5), over the scene's contact.tolerance and contact.relative_tolerance; ranges by core's rule.
// `which`: the runs they apply to, for the help text.
void addContactToleranceOptions(CLI::App& command, core::ContactTolerances& o, const std::string& which);

// Adds the subcommand `name` to `app`: its options registered by `addOptions`, run by `run` once
// parsed (each command's addNAMECommand, app/commands.h).
template <class Options>
Command addCommand(CLI::App& app, const std::string& name, const std::string& description,
                   void (*addOptions)(CLI::App&, Options&), int (*run)(const Options&))
{
    auto options = std::make_shared<Options>();
    CLI::App* parser = app.add_subcommand(name, description);
    addOptions(*parser, *options);
    return {parser, [options, run] { return run(*options); }};
}

} // namespace frontier::app
