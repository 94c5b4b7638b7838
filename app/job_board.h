// app/job_board.h: one progress line per job for batch commands. On a terminal the lines are
// redrawn in place (at most ten times a second); otherwise each job prints one line when it ends.
#pragma once

#include "app/job_result.h"

#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace frontier::app
{

class JobBoard
{
  public:
    JobBoard(std::vector<std::string> names, bool terminal);
    void update(std::size_t job, const std::string& status); // thread-safe
    void finish(std::size_t job, const std::string& status); // thread-safe
    void close();

  private:
    void redraw(bool force);
    std::vector<std::string> mNames;
    std::vector<std::string> mStatus;
    bool mTerminal;
    bool mDrawn = false;
    std::mutex mMutex;
    std::chrono::steady_clock::time_point mLast;
};

// Runs work(job) for every job on `threads` threads; returns the largest exit code.
int runJobs(std::size_t count, int threads, const std::function<int(std::size_t)>& work);

// One job of a batch: reports progress through `status`; returns its exit code, its summary
// (printed on stdout at the end, in job order) and its error.
using BatchJob = std::function<JobResult(std::size_t job, const JobStatus& status)>;

// Runs the named jobs in parallel (`threads`), one progress line each, a failing job reported on
// its line while the others finish; with one job, only a failure is reported. Returns the worst
// exit code.
int runBatch(const std::vector<std::string>& names, int threads, bool quiet, const BatchJob& work);

} // namespace frontier::app
