// tests/app/batch_slurm_test.cpp: the scripts of `frontier batch --slurm` against hostile values.
// The quoting they share with the shell (app/batch/shell_quote.h) gives the same text back through bash
// and through sbatch's reading of #SBATCH lines; a plan path, --out, --package-path and --chart
// with spaces, quotes, $(...), backticks, '%' and '#' reach the commands as data, and what cannot go
// onto an #SBATCH line (a line break, a backslash in --out, a partition or time limit Slurm would
// not take) is refused with exit 2 naming the option; the options the jobs need (--package-path)
// reach the tasks and the merge as absolute paths. No Slurm needed: the scripts run under bash
// with the environment of an array task, and the printed submit command with a stand-in sbatch
// (tests/slurm/ submits them to a real cluster).
#include "app_test_util.h"

#include <cctype>
#include <cstdlib>
#include <gtest/gtest.h>
#include <regex>
#include <set>
#include <sstream>

namespace
{
using frontier::app::test::readText;
using frontier::app::test::Result;
using frontier::app::test::shellQuote;
using frontier::app::test::sourcePath;
using frontier::app::test::TestDir;
namespace fs = std::filesystem;

// Texts the shell or sbatch would read as more than data if they were pasted unquoted.
const std::vector<std::string> cHostileTexts = {
    "",
    "plain",
    "two words",
    "it's",
    "\"double\"",
    "$(touch injected-dollar)",
    "`touch injected-tick`",
    "a\\b",
    "%a %j %% 100%",
    "x;y&z|w",
    "# not a comment",
    "'",
    "\\",
    "''\\''",
    "*?[glob]",
    "~root",
    "-leading-dash",
    "tab\there",
};

// The arguments of an #SBATCH line's text (after "#SBATCH") as sbatch takes them (its man page):
// whitespace separates them, '...' and "..." group characters, a backslash takes the next
// character as it is (also inside quotes), an unquoted # ends the line.
std::vector<std::string> sbatchArguments(const std::string& text)
{
    std::vector<std::string> words;
    std::string word;
    bool inWord = false;
    char quote = 0;
    for (std::size_t k = 0; k < text.size(); ++k)
    {
        const char c = text[k];
        if (c == '\\' && k + 1 < text.size())
        {
            word += text[++k];
            inWord = true;
        }
        else if (quote != 0)
        {
            if (c == quote)
            {
                quote = 0;
            }
            else
            {
                word += c;
            }
        }
        else if (c == '\'' || c == '"')
        {
            quote = c;
            inWord = true;
        }
        else if (c == '#')
        {
            break;
        }
        else if (std::isspace(static_cast<unsigned char>(c)) != 0)
        {
            if (inWord)
            {
                words.push_back(word);
            }
            word.clear();
            inWord = false;
        }
        else
        {
            word += c;
            inWord = true;
        }
    }
    if (inWord)
    {
        words.push_back(word);
    }
    return words;
}

// The #SBATCH lines sbatch reads (those before the first line that is no comment), as arguments.
std::vector<std::vector<std::string>> directives(const std::string& script)
{
    std::vector<std::vector<std::string>> out;
    std::istringstream in(script);
    std::string line;
    while (std::getline(in, line))
    {
        if (line.rfind("#SBATCH", 0) == 0)
        {
            out.push_back(sbatchArguments(line.substr(7)));
        }
        else if (!line.empty() && line[0] != '#')
        {
            break;
        }
    }
    return out;
}

// Runs `script` (a file) with bash in `cwd`, stdout and stderr to `log`; its exit code.
int runBash(const fs::path& script, const fs::path& cwd, const fs::path& log,
            const std::string& environment = "")
{
    const std::string command = "cd " + shellQuote(cwd.string()) + " && env " + environment + " bash " +
                                shellQuote(script.string()) + " >" + shellQuote(log.string()) + " 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> splitAtNul(const std::string& text)
{
    std::vector<std::string> words;
    std::size_t start = 0;
    for (std::size_t end = text.find('\0'); end != std::string::npos; end = text.find('\0', start))
    {
        words.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return words;
}

// The words of a script's command as bash hands them over: the script run with its `exec ` replaced
// by a printf of every word (so nothing is started), in `cwd`.
std::vector<std::string> commandWords(const std::string& script, const TestDir& dir)
{
    std::string text = readText(script);
    const std::size_t at = text.find("\nexec ");
    EXPECT_NE(at, std::string::npos) << text;
    if (at == std::string::npos)
    {
        return {};
    }
    text.replace(at + 1, 5, "printf '%s\\0' ");
    const std::string stub = dir.write("printed.sh", text);
    const fs::path words = dir.path() / "words.bin";
    EXPECT_EQ(runBash(stub, dir.path(), words, "SLURM_ARRAY_TASK_ID=0"), 0) << readText(words);
    return splitAtNul(readText(words));
}

// Files named injected* anywhere under `folder`: what a command on the side would have made.
std::vector<std::string> injected(const fs::path& folder)
{
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
    {
        if (entry.path().filename().string().rfind("injected", 0) == 0)
        {
            found.push_back(entry.path().string());
        }
    }
    return found;
}

// A Slurm --output pattern naming `path` itself: '%' doubled.
std::string literalPattern(const std::string& path)
{
    std::string out;
    for (const char c : path)
    {
        out += c == '%' ? std::string("%%") : std::string(1, c);
    }
    return out;
}

std::string batchBinary()
{
    return fs::canonical(std::string(FRONTIER_BINARY_DIR) + "/app/frontier").string();
}

// Two jobs of 0.05 s.
std::string twoJobPlan()
{
    return "scenes: [" + sourcePath("scenes/pendulum.yaml") +
           "]\n"
           "duration: 0.05\n"
           "outputs: [stats]\n"
           "vary:\n"
           "  dt: [0.001, 0.002]\n";
}

// The quoting gives every text back as one word: from bash, and from sbatch's #SBATCH reading (a
// line break aside, which --slurm refuses there); nothing quoted runs.
TEST(ShellQuote, GivesTheTextBackThroughBashAndSbatch)
{
    const TestDir dir;
    std::vector<std::string> texts = cHostileTexts;
    texts.push_back("line\nbreak $(touch injected-newline)");
    std::string script;
    for (const std::string& text : texts)
    {
        script += "printf '%s\\0' " + shellQuote(text) + "\n";
        if (text.find('\n') == std::string::npos)
        {
            EXPECT_EQ(sbatchArguments(" " + shellQuote("--output=" + text)),
                      std::vector<std::string>{"--output=" + text})
                << shellQuote(text);
        }
    }
    const std::string file = dir.write("quoted.sh", script);
    const fs::path printed = dir.path() / "printed.bin";
    ASSERT_EQ(runBash(file, dir.path(), printed), 0) << readText(printed);
    EXPECT_EQ(splitAtNul(readText(printed)), texts);
    EXPECT_TRUE(injected(dir.path()).empty()) << injected(dir.path()).front();
}

// A plan path, --out, --package-path and --chart full of shell syntax, '%' and '#': both scripts
// pass `bash -n`, every #SBATCH line is one argument with the value given (the log folder's '%'
// doubled, so Slurm expands only %a), the commands get exactly the words given (paths absolute),
// the printed submit command and --submit hand sbatch the scripts' paths, a task run as Slurm would
// run it does its shard, and nothing injected runs anywhere.
TEST(BatchSlurm, HostileValuesStayData)
{
    const TestDir dir;
    const std::string plan = dir.write("it's $(touch injected-plan) `x` 50%.yaml", twoJobPlan());
    const std::string out = dir.out("o 'q' \"d\" $(touch injected-out) `touch injected-tick` 100% #h");
    const std::string packages = "pk\n$(touch injected-pkg) 'x'";
    const std::string chartColumn = "$(touch injected-chart)";
    const Result written =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) +
                " --slurm --shards 2 --partition debug,gpu.a-1_x --time 1-02:03:04 --package-path " +
                shellQuote(packages) + " --package-path arm6_description=rel/dir --chart " +
                shellQuote("dt," + chartColumn));
    ASSERT_EQ(written.exitCode, 0) << written.err;
    const std::string batchScript = out + "/slurm/batch.sbatch";
    const std::string mergeScript = out + "/slurm/merge.sbatch";
    for (const std::string& script : {batchScript, mergeScript})
    {
        EXPECT_EQ(std::system(("bash -n " + shellQuote(script)).c_str()), 0) << readText(script);
    }

    const std::string logs = literalPattern(out + "/slurm");
    EXPECT_EQ(directives(readText(batchScript)),
              (std::vector<std::vector<std::string>>{{"--job-name=frontier-batch"},
                                                     {"--output=" + logs + "/shard-%a.out"},
                                                     {"--partition=debug,gpu.a-1_x"},
                                                     {"--time=1-02:03:04"},
                                                     {"--array=0-1"},
                                                     {"--cpus-per-task=1"}}))
        << readText(batchScript);
    EXPECT_EQ(directives(readText(mergeScript)),
              (std::vector<std::vector<std::string>>{{"--job-name=frontier-merge"},
                                                     {"--output=" + logs + "/merge.out"},
                                                     {"--partition=debug,gpu.a-1_x"},
                                                     {"--time=1-02:03:04"}}))
        << readText(mergeScript);

    const std::vector<std::string> common = {batchBinary(),
                                             "batch",
                                             plan,
                                             "--out=" + out,
                                             "--package-path=" + sourcePath(packages),
                                             "--package-path=arm6_description=" + sourcePath("rel/dir")};
    std::vector<std::string> task = common;
    task.insert(task.end(), {"--jobs", "1", "--shards", "2", "--shard-from-env", "SLURM_ARRAY_TASK_ID"});
    EXPECT_EQ(commandWords(batchScript, dir), task);
    std::vector<std::string> merge = common;
    merge.insert(merge.end(), {"--merge", "--chart=dt," + chartColumn});
    EXPECT_EQ(commandWords(mergeScript, dir), merge);

    // The printed submit command, run with a stand-in sbatch that records its arguments.
    const fs::path bin = dir.path() / "bin";
    const fs::path calls = dir.path() / "calls";
    fs::create_directories(bin);
    fs::create_directories(calls);
    dir.write("bin/sbatch",
              "#!/bin/bash\nn=$(ls \"$SBATCH_CALLS\" | wc -l)\n"
              "printf '%s\\0' \"$@\" > \"$SBATCH_CALLS/$n\"\nprintf '%s\\n' \"${SBATCH_ID:-42}\"\n");
    fs::permissions(bin / "sbatch", fs::perms::owner_exec, fs::perm_options::add);
    const std::string environment =
        "PATH=" + shellQuote(bin.string()) + ":\"$PATH\" SBATCH_CALLS=" + shellQuote(calls.string());
    const std::string prefix = "Submit with: ";
    const std::size_t at = written.out.find(prefix);
    ASSERT_NE(at, std::string::npos) << written.out;
    const std::string submit =
        written.out.substr(at + prefix.size(), written.out.find('\n', at) - at - prefix.size());
    const fs::path submitLog = dir.path() / "submit.txt";
    ASSERT_EQ(runBash(dir.write("submit.sh", submit + "\n"), dir.path(), submitLog, environment), 0)
        << submit << "\n"
        << readText(submitLog);
    EXPECT_EQ(splitAtNul(readText(calls / "0")), (std::vector<std::string>{"--parsable", batchScript}));
    EXPECT_EQ(splitAtNul(readText(calls / "1")),
              (std::vector<std::string>{"--dependency=afterok:42", mergeScript}));

    // --submit with the same stand-in; an sbatch that prints no job id submits no merge.
    fs::remove_all(calls);
    fs::create_directories(calls);
    const std::string again = "batch " + shellQuote(plan) + " --out " + shellQuote(out) +
                              " --slurm --shards 2 --submit --package-path " + shellQuote(packages);
    const std::string submitRun =
        dir.write("submit-run.sh",
                  "cd " + shellQuote(FRONTIER_SOURCE_DIR) + " && " + shellQuote(batchBinary()) + " " + again);
    ASSERT_EQ(runBash(submitRun, dir.path(), submitLog, environment), 0) << readText(submitLog);
    EXPECT_NE(readText(submitLog).find("Submitted the array job 42 and the merge job 42."), std::string::npos)
        << readText(submitLog);
    EXPECT_EQ(splitAtNul(readText(calls / "1")),
              (std::vector<std::string>{"--parsable", "--dependency=afterok:42", mergeScript}));
    fs::remove_all(calls);
    fs::create_directories(calls);
    EXPECT_EQ(runBash(submitRun, dir.path(), submitLog,
                      environment + " SBATCH_ID=" + shellQuote("$(touch injected-id)")),
              1);
    EXPECT_NE(readText(submitLog).find("printed no job id"), std::string::npos) << readText(submitLog);
    EXPECT_FALSE(fs::exists(calls / "1")) << "a merge was submitted after an sbatch that printed no job id";

    // Task 0 run as Slurm runs it, from another folder: its shard's job is done.
    const fs::path taskLog = dir.path() / "task.txt";
    ASSERT_EQ(runBash(batchScript, dir.path(), taskLog,
                      "SLURM_ARRAY_JOB_ID=7 SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=2"),
              0)
        << readText(taskLog);
    EXPECT_NE(readText(taskLog).find("1 jobs (shard 0 of 2): 1 run"), std::string::npos) << readText(taskLog);

    EXPECT_TRUE(injected(dir.path()).empty()) << injected(dir.path()).front();
    for (const auto& entry : fs::directory_iterator(FRONTIER_SOURCE_DIR)) // where `frontier` ran
    {
        EXPECT_NE(entry.path().filename().string().rfind("injected", 0), 0U) << entry.path();
    }
}

// What cannot go onto an #SBATCH line is refused before anything is written: exit 2, the option
// named with what it takes.
TEST(BatchSlurm, RefusesWhatAnSbatchLineCannotCarry)
{
    const TestDir dir;
    const std::string plan = dir.write("plan.yaml", twoJobPlan());
    const std::string out = dir.out("s");
    struct Case
    {
        std::string flags;
        std::string message;
    };
    const std::string controlOut = "--out: error: a control character (byte 0x0a at position ";
    const std::string partition = "--partition: error: expected a Slurm partition name";
    const std::string time = "--time: error: expected a Slurm time limit";
    const std::vector<Case> cases = {
        {"--out " + shellQuote(out + "\n#SBATCH --wrap=touch injected"), controlOut},
        {"--out " + shellQuote(out + "\r"), "--out: error: a control character (byte 0x0d at position "},
        {"--out " + shellQuote(out + "\\x"), "--out: error: '" + out + "\\x/slurm' holds a backslash"},
        {"--out " + shellQuote(out + "-HetJob"), "holds 'hetjob', which sbatch reads"},
        {"--partition " + shellQuote("debug\ntouch injected"),
         "--partition: error: a control character (byte 0x0a at position 6)"},
        {"--partition " + shellQuote("a b"), partition},
        {"--partition " + shellQuote("p;touch injected"), partition},
        {"--partition " + shellQuote("'p'"), partition},
        {"--partition " + shellQuote("a,,b"), partition},
        {"--partition " + shellQuote(",a"), partition},
        {"--partition packjob", "holds 'packjob'"},
        {"--time " + shellQuote("1:00:00\n#SBATCH --wrap=x"),
         "--time: error: a control character (byte 0x0a"},
        {"--time abc", time},
        {"--time 1-", time},
        {"--time=-1", time},
        {"--time 1:2:3:4", time},
        {"--time 1-2:3:4:5", time},
        {"--time 1.5", time},
        {"--time 1--2", time},
        {"--time 1-2-3", time},
        {"--time :30", time},
        {"--time 30:", time},
        {"--time " + shellQuote("1 0"), time},
        {"--time 99999999999", time},
        {"--time 24856-0", time}, // 2^31 s and more: past what Slurm counts
    };
    for (const Case& c : cases)
    {
        const std::string flags =
            c.flags.rfind("--out", 0) == 0 ? c.flags : "--out " + shellQuote(out) + " " + c.flags;
        const Result r = dir.run("batch " + shellQuote(plan) + " --slurm " + flags);
        EXPECT_EQ(r.exitCode, 2) << c.flags << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("frontier: ", 0), 0U) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.flags << "\n" << r.err;
        EXPECT_TRUE(dir.outputs().empty()) << c.flags << ": wrote " << dir.outputs().front();
        EXPECT_TRUE(injected(dir.path()).empty()) << injected(dir.path()).front();
    }
    // Every form sbatch takes.
    for (const char* limit :
         {"0", "30", "30:00", "1:00:00", "2-12", "2-12:30", "2-12:30:15", "24855-0", "unlimited", "INFINITE"})
    {
        const Result r = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) +
                                 " --slurm --time " + std::string(limit));
        EXPECT_EQ(r.exitCode, 0) << limit << "\n" << r.err;
        EXPECT_NE(readText(out + "/slurm/batch.sbatch").find("#SBATCH '--time=" + std::string(limit) + "'\n"),
                  std::string::npos)
            << limit;
    }
}

// A plan whose URDF finds its meshes only through --package-path (given relative to the folder it
// is run from) runs in the array's tasks, started from another folder, and merges there.
TEST(BatchSlurm, TasksAndMergeGetThePackagePaths)
{
    const TestDir dir;
    const fs::path urdf = dir.path() / "arm6.urdf"; // away from its package: found only by the flags
    fs::copy_file(sourcePath("scenes/robots/arm6_description/urdf/arm6.urdf"), urdf);
    const std::string plan = dir.write("plan.yaml", "scenes: [" + urdf.string() +
                                                        "]\nduration: 0.01\noutputs: [stats]\n"
                                                        "vary:\n  dt: [0.001, 0.002]\n");
    const Result without = dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(dir.out("local")));
    ASSERT_EQ(without.exitCode, 1) << "the plan runs without --package-path; it tests nothing\n"
                                   << without.err;
    EXPECT_NE(without.err.find("arm6_description"), std::string::npos) << without.err;

    const std::string out = dir.out("s");
    const std::string packages = " --package-path scenes/robots --package-path "
                                 "arm6_description=scenes/robots/arm6_description";
    const Result written =
        dir.run("batch " + shellQuote(plan) + " --out " + shellQuote(out) + " --slurm --shards 2" + packages);
    ASSERT_EQ(written.exitCode, 0) << written.err;
    for (const char* script : {"batch.sbatch", "merge.sbatch"})
    {
        const std::string text = readText(out + "/slurm/" + script);
        EXPECT_NE(text.find(" '--package-path=" + sourcePath("scenes/robots") + "' "), std::string::npos)
            << text;
        EXPECT_NE(text.find(" '--package-path=arm6_description=" +
                            sourcePath("scenes/robots/arm6_description") + "'"),
                  std::string::npos)
            << text;
    }
    for (int task = 0; task < 2; ++task)
    {
        const fs::path log = dir.path() / ("task" + std::to_string(task) + ".txt");
        EXPECT_EQ(runBash(out + "/slurm/batch.sbatch", dir.path(), log,
                          "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " SLURM_ARRAY_TASK_COUNT=2"),
                  0)
            << readText(log);
    }
    const fs::path log = dir.path() / "merge.txt";
    EXPECT_EQ(runBash(out + "/slurm/merge.sbatch", dir.path(), log), 0) << readText(log);
    EXPECT_TRUE(fs::exists(out + "/batch.csv"));
}

// Every option of `frontier batch` is one the scripts handle: forwarded to the tasks and the merge
// when it changes what a job does or where it finds its files (forwardedOptions in
// app/batch/slurm.cpp), or turned into the scripts' own settings. An option added to `batch` fails
// here until it is sorted into one of these.
TEST(BatchSlurm, EveryBatchOptionIsForwardedOrTakenByTheScripts)
{
    const TestDir dir;
    const Result help = dir.run("batch --help");
    ASSERT_EQ(help.exitCode, 0) << help.err;
    std::set<std::string> options;
    const std::regex option(R"(^\s+(?:-\w,\s*)?(--[a-z][a-z-]*))");
    std::istringstream in(help.out);
    std::string line;
    while (std::getline(in, line))
    {
        std::smatch match;
        if (std::regex_search(line, match, option))
        {
            options.insert(match[1]);
        }
    }
    const std::set<std::string> forwarded = {"--package-path", "--quiet", "--chart"};
    const std::set<std::string> scripts = {
        "--out",  "--shards", "--slurm", "--partition",
        "--time", "--cpus",   "--submit"}; // the scripts' own, or the array's
    const std::set<std::string> notWithSlurm = {
        "--help",           "--list", "--shard",
        "--shard-from-env", "--jobs", "--merge"}; // each task's own (from --cpus, the array), or none
    std::set<std::string> known = forwarded;
    known.insert(scripts.begin(), scripts.end());
    known.insert(notWithSlurm.begin(), notWithSlurm.end());
    EXPECT_EQ(options, known) << help.out;
}

} // namespace
