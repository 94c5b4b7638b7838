// app/batch/slurm.cpp: `frontier batch --slurm`: DIR/slurm/batch.sbatch (an array job, task I
// running `frontier batch PLAN --out DIR --shards N --shard-from-env SLURM_ARRAY_TASK_ID`, shard I
// of N) and DIR/slurm/merge.sbatch; with --submit, sbatch runs both, the merge after the array
// succeeded (afterok).
#include "app/batch/batch.h"
#include "app/batch/shell_quote.h"
#include "io/atomic_file.h"
#include "io/package_paths.h"
#include "io/scene.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace frontier::app
{

namespace
{
namespace fs = std::filesystem;

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

std::string lowerCase(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

// What goes onto an #SBATCH line: quoting keeps it one argument there, but a line break (or any
// control character) would end the line and start a line of the script; and sbatch takes a line
// holding "hetjob" or "packjob" anywhere for the separator of a heterogeneous job's components.
void checkDirectiveValue(const std::string& flag, const std::string& value, const std::string& expected)
{
    for (std::size_t k = 0; k < value.size(); ++k)
    {
        const auto c = static_cast<unsigned char>(value[k]);
        if (c < 0x20 || c == 0x7f)
        {
            char byte[8];
            std::snprintf(byte, sizeof byte, "0x%02x", c);
            throw io::InputError(flag, 0, 0,
                                 "a control character (byte " + std::string(byte) + " at position " +
                                     std::to_string(k + 1) + ") cannot go onto an #SBATCH line; expected " +
                                     expected + " of printable characters");
        }
    }
    for (const char* word : {"hetjob", "packjob"})
    {
        if (lowerCase(value).find(word) != std::string::npos)
        {
            throw io::InputError(flag, 0, 0,
                                 "'" + value + "' holds '" + word +
                                     "', which sbatch reads on an #SBATCH line as the start of another "
                                     "component of a heterogeneous job; expected " +
                                     expected + " without it");
        }
    }
}

// Whole numbers separated by `separator`, each of 1 to 9 digits; false for anything else.
bool splitNumbers(const std::string& text, char separator, std::vector<long long>& numbers)
{
    std::size_t start = 0;
    while (true)
    {
        const std::size_t end = std::min(text.find(separator, start), text.size());
        const std::string field = text.substr(start, end - start);
        if (field.empty() || field.size() > 9 ||
            !std::all_of(field.begin(), field.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
        {
            return false;
        }
        numbers.push_back(std::stoll(field));
        if (end == text.size())
        {
            return true;
        }
        start = end + 1;
    }
}

// A time limit sbatch --time takes (its man page): MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS,
// DAYS-HOURS, DAYS-HOURS:MINUTES, DAYS-HOURS:MINUTES:SECONDS, or UNLIMITED (INFINITE), within the
// seconds Slurm counts in an int.
bool isSlurmTime(const std::string& text)
{
    if (lowerCase(text) == "unlimited" || lowerCase(text) == "infinite")
    {
        return true;
    }
    const std::size_t dash = text.find('-');
    long long days = 0;
    long long hours = 0;
    long long minutes = 0;
    long long seconds = 0;
    std::vector<long long> fields; // colon-separated, after DAYS- when there is one
    if (dash != std::string::npos)
    {
        std::vector<long long> day;
        if (!splitNumbers(text.substr(0, dash), ':', day) || day.size() != 1 ||
            !splitNumbers(text.substr(dash + 1), ':', fields) || fields.size() > 3)
        {
            return false;
        }
        days = day.front();
        fields.resize(3, 0);
        hours = fields[0];
        minutes = fields[1];
        seconds = fields[2];
    }
    else
    {
        if (!splitNumbers(text, ':', fields) || fields.size() > 3)
        {
            return false;
        }
        if (fields.size() == 3)
        {
            hours = fields[0];
        }
        minutes = fields[fields.size() == 3 ? 1 : 0];
        seconds = fields.size() == 1 ? 0 : fields.back();
    }
    return ((days * 24 + hours) * 60 + minutes) * 60 + seconds <= std::numeric_limits<int>::max();
}

// One partition name or several separated by commas (sbatch --partition takes a list).
bool isPartitionList(const std::string& text)
{
    std::size_t start = 0;
    while (true)
    {
        const std::size_t end = std::min(text.find(',', start), text.size());
        if (end == start || !std::all_of(text.begin() + static_cast<std::ptrdiff_t>(start),
                                         text.begin() + static_cast<std::ptrdiff_t>(end),
                                         [](unsigned char c) {
                                             return std::isalnum(c) != 0 || c == '_' || c == '-' || c == '.';
                                         }))
        {
            return false;
        }
        if (end == text.size())
        {
            return true;
        }
        start = end + 1;
    }
}

// Throws io::InputError naming the option when a value of the scripts' #SBATCH lines cannot go there.
void checkSlurmOptions(const BatchOptions& options, const std::string& logFolder)
{
    checkDirectiveValue("--out", logFolder, "a path");
    if (logFolder.find('\\') != std::string::npos)
    {
        throw io::InputError(
            "--out", 0, 0,
            "'" + logFolder +
                "' holds a backslash: Slurm drops every backslash of an --output path and then "
                "expands no %a (the array task); expected a path without '\\'");
    }
    checkDirectiveValue("--partition", options.partition, "a partition name");
    if (!options.partition.empty() && !isPartitionList(options.partition))
    {
        throw io::InputError("--partition", 0, 0,
                             "expected a Slurm partition name, or several separated by commas, of letters, "
                             "digits, '_', '-' and '.', got '" +
                                 options.partition + "'");
    }
    checkDirectiveValue("--time", options.time, "a time limit");
    if (!options.time.empty() && !isSlurmTime(options.time))
    {
        throw io::InputError("--time", 0, 0,
                             "expected a Slurm time limit: MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, "
                             "DAYS-HOURS, DAYS-HOURS:MINUTES or DAYS-HOURS:MINUTES:SECONDS (whole numbers, "
                             "at most 2^31 - 1 seconds in all), or UNLIMITED; got '" +
                                 options.time + "'");
    }
}

// A path of the log folder as an --output pattern: Slurm expands %a (the array task), %j and the
// like there, and %% to one '%'.
std::string outputPattern(const std::string& folder, const std::string& name)
{
    std::string out;
    for (const char c : folder)
    {
        out += c == '%' ? std::string("%%") : std::string(1, c);
    }
    return out + "/" + name;
}

std::string header(const BatchOptions& options, const std::string& name, const std::string& log)
{
    std::string text =
        "#!/bin/bash\n#SBATCH --job-name=" + name + "\n#SBATCH " + shellQuote("--output=" + log) + "\n";
    if (!options.partition.empty())
    {
        text += "#SBATCH " + shellQuote("--partition=" + options.partition) + "\n";
    }
    if (!options.time.empty())
    {
        text += "#SBATCH " + shellQuote("--time=" + options.time) + "\n";
    }
    return text;
}

// The options of this command that the tasks and the merge need as well: where the jobs' URDFs
// find their packages (absolute: a task may start in another folder; the merge's inputs digests
// depend on them too), and --quiet.
std::string forwardedOptions(const BatchOptions& options)
{
    std::string text;
    for (const std::string& entry : options.urdf.packagePaths)
    {
        const io::detail::PackagePathEntry split = io::detail::splitPackagePathEntry(entry);
        text += " " + shellQuote("--package-path=" + (split.name.empty() ? "" : split.name + "=") +
                                 absolute(split.dir));
    }
    if (options.quiet)
    {
        text += " --quiet";
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

namespace
{
// The two scripts of DIR/slurm/.
struct SlurmScripts
{
    std::string batch; // the array job
    std::string merge; // the merge after it
};

// Writes both scripts: the array job of `shards` tasks (each one shard, --jobs from --cpus), and
// the merge. Throws io::OutputError, std::filesystem::filesystem_error.
SlurmScripts writeSlurmScripts(const BatchOptions& options, const fs::path& folder, int jobs, int shards)
{
    // Every word of the commands quoted (app/batch/shell_quote.h); options as --name=VALUE, so that no
    // value can pass for an option.
    const std::string command = "exec " + shellQuote(selfPath()) + " batch " +
                                shellQuote(absolute(options.plan)) + " " +
                                shellQuote("--out=" + absolute(options.out)) + forwardedOptions(options);
    const SlurmScripts scripts{(folder / "batch.sbatch").string(), (folder / "merge.sbatch").string()};
    fs::create_directories(folder);
    std::string batch = header(options, "frontier-batch", outputPattern(folder.string(), "shard-%a.out"));
    batch += "#SBATCH --array=0-" + std::to_string(std::max(shards, 1) - 1) + "\n";
    batch += "#SBATCH --cpus-per-task=" + std::to_string(options.cpus) + "\n";
    // The shard is the task id itself, not its rank in the array: `sbatch --array=1 batch.sbatch`
    // reruns shard 1 of N alone (Slurm's task count would be 1 there).
    batch += "# " + std::to_string(jobs) + " jobs in " + std::to_string(shards) +
             " shards: task I runs the jobs whose index mod " + std::to_string(shards) +
             " is I; sbatch --array=I reruns task I alone.\n";
    batch += command + " --jobs " + std::to_string(options.cpus) + " --shards " + std::to_string(shards) +
             " --shard-from-env SLURM_ARRAY_TASK_ID\n";
    writeScript(scripts.batch, batch);
    std::string merge = header(options, "frontier-merge", outputPattern(folder.string(), "merge.out"));
    merge += command + " --merge";
    if (options.chart.size() == 2)
    {
        merge += " " + shellQuote("--chart=" + options.chart[0] + "," + options.chart[1]);
    }
    writeScript(scripts.merge, merge + "\n");
    return scripts;
}

// --submit: sbatch the array, then the merge after it (afterok). Returns the exit code.
int submitScripts(const SlurmScripts& scripts)
{
    const std::optional<std::string> array = capture("sbatch --parsable " + shellQuote(scripts.batch));
    const std::string arrayId =
        array ? array->substr(0, array->find(';')) : ""; // "ID;CLUSTER" when federated
    if (arrayId.empty() ||
        !std::all_of(arrayId.begin(), arrayId.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
    {
        std::cerr << "frontier: sbatch " << scripts.batch << " failed"
                  << (arrayId.empty() ? std::string() : " (it printed no job id but '" + *array + "')")
                  << "\n";
        return cExitFailed;
    }
    const std::optional<std::string> merged =
        capture("sbatch --parsable --dependency=afterok:" + arrayId + " " + shellQuote(scripts.merge));
    if (!merged || merged->empty())
    {
        std::cerr << "frontier: sbatch " << scripts.merge << " failed (the array job " << arrayId
                  << " is submitted)\n";
        return cExitFailed;
    }
    std::printf("Submitted the array job %s and the merge job %s.\n", arrayId.c_str(),
                merged->substr(0, merged->find(';')).c_str());
    return cExitOk;
}
} // namespace

int slurmBatch(const BatchPlan& plan, const BatchOptions& options)
{
    const int jobs = static_cast<int>(plan.jobs.size());
    const int shards = std::min(options.shards.value_or(std::min(jobs, 100)), jobs);
    const fs::path folder = fs::path(absolute(options.out)) / "slurm";
    SlurmScripts scripts;
    try
    {
        checkSlurmOptions(options, folder.string());
        scripts = writeSlurmScripts(options, folder, jobs, shards);
    }
    catch (const io::InputError& e)
    {
        std::cerr << "frontier: " << e.what() << "\n";
        return cExitBadInput;
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
    std::printf("Wrote %s (%d jobs in an array of %d tasks) and %s.\n", scripts.batch.c_str(), jobs, shards,
                scripts.merge.c_str());
    if (!options.submit)
    {
        std::printf("Submit with: id=$(sbatch --parsable %s) && sbatch --dependency=afterok:${id%%%%;*} %s\n",
                    shellQuote(scripts.batch).c_str(), shellQuote(scripts.merge).c_str());
        return cExitOk;
    }
    return submitScripts(scripts);
}

} // namespace frontier::app
