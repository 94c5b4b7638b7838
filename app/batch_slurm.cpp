// app/batch_slurm.cpp: `frontier batch --slurm`: DIR/slurm/batch.sbatch (an array job, task I
// running `frontier batch PLAN --out DIR --shards N --shard-from-env SLURM_ARRAY_TASK_ID`, shard I
// of N) and DIR/slurm/merge.sbatch; with --submit, sbatch runs both, the merge after the array
// succeeded (afterok).
#include "app/batch_jobs.h"
#include "io/atomic_file.h"
#include "io/scene.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

// Single quotes for the shell.
std::string shellQuote(const std::string& s)
{
    std::string out = "'";
    for (const char c : s)
    {
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return out + "'";
}

std::string absolute(const std::string& path)
{
    return fs::absolute(path).lexically_normal().string();
}

// This executable's path, so the scripts run the same binary.
std::string selfPath()
{
    std::error_code error;
    const fs::path self = fs::read_symlink("/proc/self/exe", error);
    return error ? std::string("frontier") : self.string();
}

std::string header(const BatchOptions& options, const std::string& name, const std::string& log)
{
    std::string text = "#!/bin/bash\n#SBATCH --job-name=" + name + "\n#SBATCH --output=" + log + "\n";
    if (!options.partition.empty())
    {
        text += "#SBATCH --partition=" + options.partition + "\n";
    }
    if (!options.time.empty())
    {
        text += "#SBATCH --time=" + options.time + "\n";
    }
    return text;
}

void writeScript(const fs::path& path, const std::string& text)
{
    io::AtomicFile file(path.string());
    file.write(text);
    file.commit();
    fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                    fs::perm_options::add);
}

// Runs `command` through the shell; its stdout, or nullopt when it failed (its stderr passes through).
std::optional<std::string> capture(const std::string& command)
{
    std::FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr)
    {
        return std::nullopt;
    }
    std::string out;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr)
    {
        out += buffer;
    }
    const int status = ::pclose(pipe);
    if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
        return std::nullopt;
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == '\r'))
    {
        out.pop_back();
    }
    return out;
}
} // namespace

int slurmBatch(const BatchPlan& plan, const BatchOptions& options)
{
    const int jobs = static_cast<int>(plan.jobs.size());
    const int shards = std::min(options.shards.value_or(std::min(jobs, 100)), jobs);
    const fs::path folder = fs::path(absolute(options.out)) / "slurm";
    const std::string self = shellQuote(selfPath());
    const std::string planPath = shellQuote(absolute(options.plan));
    const std::string out = shellQuote(absolute(options.out));
    const std::string batchScript = (folder / "batch.sbatch").string();
    const std::string mergeScript = (folder / "merge.sbatch").string();
    try
    {
        fs::create_directories(folder);
        std::string batch = header(options, "frontier-batch", (folder / "shard-%a.out").string());
        batch += "#SBATCH --array=0-" + std::to_string(std::max(shards, 1) - 1) + "\n";
        batch += "#SBATCH --cpus-per-task=" + std::to_string(options.cpus) + "\n";
        // The shard is the task id itself, not its rank in the array: `sbatch --array=1 batch.sbatch`
        // reruns shard 1 of N alone (Slurm's task count would be 1 there).
        batch += "# " + std::to_string(jobs) + " jobs in " + std::to_string(shards) +
                 " shards: task I runs the jobs whose index mod " + std::to_string(shards) +
                 " is I; sbatch --array=I reruns task I alone.\n";
        batch += "exec " + self + " batch " + planPath + " --out " + out + " --jobs " +
                 std::to_string(options.cpus) + " --shards " + std::to_string(shards) +
                 " --shard-from-env SLURM_ARRAY_TASK_ID\n";
        writeScript(batchScript, batch);
        std::string merge = header(options, "frontier-merge", (folder / "merge.out").string());
        merge += "exec " + self + " batch " + planPath + " --out " + out + " --merge";
        if (options.chart.size() == 2)
        {
            merge += " --chart " + shellQuote(options.chart[0] + "," + options.chart[1]);
        }
        writeScript(mergeScript, merge + "\n");
    }
    catch (const io::OutputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    catch (const fs::filesystem_error& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
    }
    std::printf("Wrote %s (%d jobs in an array of %d tasks) and %s.\n", batchScript.c_str(), jobs, shards,
                mergeScript.c_str());
    if (!options.submit)
    {
        std::printf("Submit with: id=$(sbatch --parsable %s) && sbatch --dependency=afterok:${id%%%%;*} %s\n",
                    batchScript.c_str(), mergeScript.c_str());
        return cExitOk;
    }
    const std::optional<std::string> array = capture("sbatch --parsable " + shellQuote(batchScript));
    if (!array || array->empty())
    {
        std::cerr << "frontier: sbatch " << batchScript << " failed\n";
        return cExitFailed;
    }
    const std::string arrayId = array->substr(0, array->find(';')); // "ID;CLUSTER" on federated setups
    const std::optional<std::string> merged =
        capture("sbatch --parsable --dependency=afterok:" + arrayId + " " + shellQuote(mergeScript));
    if (!merged || merged->empty())
    {
        std::cerr << "frontier: sbatch " << mergeScript << " failed (the array job " << arrayId
                  << " is submitted)\n";
        return cExitFailed;
    }
    std::printf("Submitted the array job %s and the merge job %s.\n", arrayId.c_str(),
                merged->substr(0, merged->find(';')).c_str());
    return cExitOk;
}

} // namespace frontier::app
