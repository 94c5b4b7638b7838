// app/job_result.h: what one job of a command returns (a scene run, a trajectory rendered, a batch
// job): its exit code and its messages, printed by the command once the job is over.
#pragma once

#include "app/commands.h"

#include <functional>
#include <string>

namespace frontier::app
{

struct JobResult
{
    int exitCode = cExitOk; // app/commands.h, or run::interruptedExitCode
    std::string summary;    // the one-line summary for stdout; empty: none
    std::string error;      // what went wrong, for stderr; empty: nothing
};

// A job that stopped with `exitCode` and nothing to summarize.
inline JobResult failedJob(int exitCode, std::string error)
{
    return {exitCode, {}, std::move(error)};
}

// A job's progress, one line of text ("simulating 40%", "rendering 3 / 90 frames").
using JobStatus = std::function<void(const std::string&)>;

} // namespace frontier::app
