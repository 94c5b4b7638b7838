// tests/app/app_test_util.h: running the `frontier` executable in a per-test folder.
#pragma once

#include "app/batch/shell_quote.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace frontier::app::test
{

inline std::string sourcePath(const std::string& relative)
{
    return std::string(FRONTIER_SOURCE_DIR) + "/" + relative;
}

inline std::string readText(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// One word for /bin/sh: the quoting of the scripts `frontier` writes.
using frontier::app::shellQuote;

struct Result
{
    int exitCode = -1; // the process's exit status, -1 when it did not exit normally
    std::string out;   // its stdout
    std::string err;   // its stderr
};

// FRONTIER_BINARY_DIR/test-tmp/app.<suite>.<test>: created empty, removed with its contents at the
// end. Runs `frontier` from the source folder (so scenes/... paths work), capturing stdout and
// stderr into files of this folder.
class TestDir
{
  public:
    TestDir()
    {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("app.") + info->test_suite_name() + "." + info->name();
        for (char& c : name)
        {
            c = (c == '/') ? '_' : c;
        }
        mPath = std::filesystem::path(FRONTIER_BINARY_DIR) / "test-tmp" / name;
        std::filesystem::remove_all(mPath);
        std::filesystem::create_directories(mPath / "out");
    }
    ~TestDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(mPath, ec);
    }
    TestDir(const TestDir&) = delete;
    TestDir& operator=(const TestDir&) = delete;

    // A path in the folder "out/" that holds nothing but the command's outputs.
    std::string out(const std::string& name) const { return (mPath / "out" / name).string(); }
    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string path = (mPath / name).string();
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    const std::filesystem::path& path() const { return mPath; }

    // Runs `frontier ARGS` (ARGS already quoted for the shell where needed).
    Result run(const std::string& args) const
    {
        const std::filesystem::path out = mPath / "stdout.txt";
        const std::filesystem::path err = mPath / "stderr.txt";
        const std::string command = "cd " + shellQuote(FRONTIER_SOURCE_DIR) + " && " +
                                    shellQuote(std::string(FRONTIER_BINARY_DIR) + "/app/frontier") + " " +
                                    args + " >" + shellQuote(out.string()) + " 2>" + shellQuote(err.string());
        const int status = std::system(command.c_str());
        Result result;
        result.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
        result.out = readText(out);
        result.err = readText(err);
        return result;
    }

    // Names of the entries of out/.
    std::vector<std::string> outputs() const
    {
        std::vector<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(mPath / "out"))
        {
            names.push_back(entry.path().filename().string());
        }
        return names;
    }

  private:
    std::filesystem::path mPath;
};

// Starts `frontier ARGS` in the source folder (as TestDir::run does), stdout and stderr to
// stdout.txt and stderr.txt of the test folder; returns the child's pid.
inline pid_t spawnFrontier(const TestDir& dir, const std::vector<std::string>& args)
{
    const std::string binary = std::string(FRONTIER_BINARY_DIR) + "/app/frontier";
    const std::string out = (dir.path() / "stdout.txt").string();
    const std::string err = (dir.path() / "stderr.txt").string();
    std::vector<std::string> words = {binary};
    words.insert(words.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& word : words)
    {
        argv.push_back(word.data());
    }
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0)
    {
        const int outFd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int errFd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (outFd < 0 || errFd < 0 || ::chdir(FRONTIER_SOURCE_DIR) != 0)
        {
            ::_exit(127);
        }
        ::dup2(outFd, 1);
        ::dup2(errFd, 2);
        ::execv(binary.c_str(), argv.data());
        ::_exit(127);
    }
    return pid;
}

// The exit code of the child, waiting at most `seconds` (then it is killed: -1).
inline int waitForExit(pid_t pid, double seconds)
{
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0)
    {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
        {
            ::kill(pid, SIGKILL);
            ::waitpid(pid, &status, 0);
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Waits (at most `seconds`) until process `pid` catches `signal` (its handler is installed: the
// signal's bit in SigCgt of /proc/PID/status); false when it did not in time or has ended.
inline bool waitForHandler(pid_t pid, int signal, double seconds)
{
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds)
    {
        std::ifstream status("/proc/" + std::to_string(pid) + "/status");
        std::string line;
        while (std::getline(status, line))
        {
            if (line.rfind("SigCgt:", 0) == 0 &&
                ((std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1U) != 0)
            {
                return true;
            }
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

// Sets PATH for the lifetime of the object (the child inherits it).
class ScopedPath
{
  public:
    explicit ScopedPath(const std::string& path)
    {
        const char* old = std::getenv("PATH");
        mOld = old != nullptr ? old : "";
        setenv("PATH", path.c_str(), 1);
    }
    ~ScopedPath() { setenv("PATH", mOld.c_str(), 1); }
    ScopedPath(const ScopedPath&) = delete;
    ScopedPath& operator=(const ScopedPath&) = delete;

  private:
    std::string mOld;
};

} // namespace frontier::app::test
