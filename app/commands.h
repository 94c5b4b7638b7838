// app/commands.h: the subcommands of the `frontier` executable: their options, and for each one
// the function app/main.cpp calls to register it (in the command's file, app/NAME_command.cpp).
#pragma once

#include "io/scene.h"
#include "study/sweep.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace CLI
{
class App;
}

namespace frontier::app
{

// Exit codes (README, "Exit codes"): 0 success, 1 the run failed on its own terms, 2 bad input or
// usage; 128 + the signal when SIGINT, SIGTERM or SIGHUP stopped it (run/run_loop.h).
inline constexpr int cExitOk = 0;
inline constexpr int cExitFailed = 1;
inline constexpr int cExitBadInput = 2;

struct RunOptions
{
    std::vector<std::string> scenes; // several: a batch, run in parallel (--jobs)
    std::optional<double> duration;  // s
    std::optional<long> steps;
    std::optional<double> dt; // s
    std::optional<std::string> solver;
    std::optional<int> pgsIterations;
    std::optional<std::string> integrator;
    core::ContactTolerances contact; // --contact-tolerance, --contact-relative-tolerance
    std::string trajectory;          // CSV path, empty: none
    int recordEvery = 1;
    std::string stats;    // JSON path, empty: none
    std::string joints;   // joints CSV path (io/joints_file.h), empty: none
    std::string contacts; // contacts CSV path (io/contacts_file.h), empty: none
    std::string frames;   // PNG folder, empty: none
    double fps = 30.0;
    int width = 640;
    int height = 480;
    std::string video; // MP4 assembled from the frames with ffmpeg
    int jobs = 2;      // parallel jobs (batch) or render threads
    bool quiet = false;
    bool strict = false;  // warnings of the run (a passive scene that gained energy) fail it
    io::UrdfOptions urdf; // --package-path, --fixed-base, --free-base, --drop-height, --self-collision
    // A batch job's: the digest of its inputs (io/input_digest.h), written to the stats with the
    // files the load read; empty: neither.
    std::string inputsDigest;
};

struct RenderCommandOptions
{
    std::vector<std::string> trajectories;
    std::string scene; // empty: the scene named in each trajectory's header
    std::string frames;
    double fps = 30.0;
    int width = 640;
    int height = 480;
    std::string video;
    int jobs = 2;
    bool quiet = false;
    std::vector<std::string> packagePaths; // searched before those the trajectory was recorded with
};

struct InfoOptions
{
    std::string scene;
    bool json = false;
    io::UrdfOptions urdf;
};

// Default tolerances of `frontier check`: loose enough for another build of the same code
// (round-off grows along a trajectory), tight enough to catch a changed result.
struct CheckOptions
{
    std::string scene;
    std::string reference;
    double positionTolerance = 1e-6;        // m
    double orientationTolerance = 1e-5;     // rad
    double velocityTolerance = 1e-5;        // m/s
    double angularVelocityTolerance = 1e-4; // rad/s
    bool quiet = false;
    std::vector<std::string> packagePaths; // searched before those the reference was recorded with
};

// `frontier stability`: each scene with each method, a markdown table of what survived.
struct StabilityOptions
{
    std::vector<std::string> scenes;
    std::vector<std::string> methods; // `solver[:iterations]/integrator`; empty: the defaults
    std::string out;                  // markdown file, empty: stdout only
    std::optional<double> duration;   // s, instead of each scene's
    std::optional<double> dt;         // s, instead of each scene's
    int maxDenseRows = 2000;          // dense runs of larger KKT matrices are skipped
    bool largestDt = false;           // also search each cell's largest time step that holds
    bool quiet = false;
};

// `frontier sweep`: list entries as given (split at commas); empty lists take the defaults.
struct SweepOptions
{
    std::string scene;
    std::vector<std::string> dts;         // s; default: the scene's dt x 16, 8, 4, 2, 1
    std::vector<std::string> solvers;     // linear, dense, pgs, pgs:K; default: linear
    std::vector<std::string> integrators; // euler, rattle, rattle4; default: euler, rattle
    std::optional<double> duration;       // s; default: the scene's, at most 2 s
    core::ContactTolerances contact;      // every run but the reference's
    std::string out;                      // folder for sweep.csv, sweep.png, sweep.gp, sweep.dat
    std::string referenceCsv;             // rows t,x,y,z of one body's centre of mass, not a run's
    std::string referenceBody;            // that body's name
    study::Accuracy chartAccuracy = study::Accuracy::TrajectoryError; // the chart's y axis
    io::UrdfOptions urdf;
};

// `frontier batch` (README "Batches", docs/batch.md): a plan's jobs, resumable, sharded, merged.
struct BatchOptions
{
    std::string plan;
    std::string out;   // DIR: DIR/jobs/ID/, DIR/batch.csv, DIR/summary.md, DIR/slurm/
    bool list = false; // print the jobs, run nothing
    // --shard "I/N": only jobs whose index mod N is I
    std::optional<std::string> shard;
    bool shardFromEnv = false;      // the shard from Slurm, Kubernetes or `shardVariable`
    std::string shardVariable;      // --shard-from-env VAR: the index's variable
    std::optional<int> shards;      // shard count (--slurm's array; --shard-from-env's fallback)
    int jobs = 2;                   // jobs at a time on this machine
    bool merge = false;             // write DIR/batch.csv and DIR/summary.md
    std::vector<std::string> chart; // --chart X,Y: DIR/chart.png of column Y against X
    bool slurm = false;             // write DIR/slurm/batch.sbatch and merge.sbatch
    std::string partition;          // #SBATCH --partition
    std::string time;               // #SBATCH --time
    int cpus = 1;                   // #SBATCH --cpus-per-task, and --jobs of each shard
    bool submit = false;            // run sbatch on both scripts
    bool quiet = false;
    io::UrdfOptions urdf;
};

int runCommand(const RunOptions& options);
int batchCommand(const BatchOptions& options);
int checkCommand(const CheckOptions& options);
int infoCommand(const InfoOptions& options);
int renderCommand(const RenderCommandOptions& options);
int sweepCommand(const SweepOptions& options);
int stabilityCommand(const StabilityOptions& options);

// A subcommand registered on the command line: its parser, and what runs it once parsed (the
// command's options, filled by the parser, captured inside). `run` returns the exit code.
struct Command
{
    CLI::App* parser = nullptr;
    std::function<int()> run;
};

// Each adds its subcommand and options to `app` (in --help's order, as app/main.cpp calls them).
Command addRunCommand(CLI::App& app);
Command addInfoCommand(CLI::App& app);
Command addRenderCommand(CLI::App& app);
Command addCheckCommand(CLI::App& app);
Command addStabilityCommand(CLI::App& app);
Command addSweepCommand(CLI::App& app);
Command addBatchCommand(CLI::App& app);

} // namespace frontier::app
