// app/job_board.cpp: progress lines for parallel jobs, and the job runner.
#include "app/job_board.h"

#include "app/progress.h"

#include <atomic>
#include <cstdio>
#include <thread>

namespace frontier::app
{

JobBoard::JobBoard(std::vector<std::string> names, bool terminal)
    : mNames(std::move(names)), mStatus(mNames.size(), "waiting"), mTerminal(terminal)
{
}

void JobBoard::redraw(bool force)
{
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - mLast < std::chrono::milliseconds(100))
    {
        return;
    }
    mLast = now;
    if (mDrawn)
    {
        std::fprintf(stderr, "\033[%zuA", mNames.size());
    }
    for (std::size_t j = 0; j < mNames.size(); ++j)
    {
        std::fprintf(stderr, "\r\033[K%s: %s\n", mNames[j].c_str(), mStatus[j].c_str());
    }
    std::fflush(stderr);
    mDrawn = true;
}

void JobBoard::update(std::size_t job, const std::string& status)
{
    std::lock_guard<std::mutex> lock(mMutex);
    mStatus[job] = status;
    if (mTerminal)
    {
        redraw(false);
    }
}

void JobBoard::finish(std::size_t job, const std::string& status)
{
    std::lock_guard<std::mutex> lock(mMutex);
    mStatus[job] = status;
    if (mTerminal)
    {
        redraw(true);
    }
    else
    {
        std::fprintf(stderr, "%s: %s\n", mNames[job].c_str(), status.c_str());
    }
}

void JobBoard::close()
{
    std::lock_guard<std::mutex> lock(mMutex);
    if (mTerminal)
    {
        redraw(true);
    }
}

int runJobs(std::size_t count, int threads, const std::function<int(std::size_t)>& work)
{
    std::atomic<std::size_t> next{0};
    std::atomic<int> worst{0};
    auto worker = [&]()
    {
        for (std::size_t job = next++; job < count; job = next++)
        {
            const int code = work(job);
            int seen = worst.load();
            while (code > seen && !worst.compare_exchange_weak(seen, code))
            {
            }
        }
    };
    std::vector<std::thread> pool;
    const int n = std::max(1, std::min<int>(threads, static_cast<int>(count)));
    for (int t = 1; t < n; ++t)
    {
        pool.emplace_back(worker);
    }
    worker();
    for (std::thread& t : pool)
    {
        t.join();
    }
    return worst;
}

int runBatch(const std::vector<std::string>& names, int threads, bool quiet, const BatchJob& work)
{
    JobBoard board(names, !quiet && stderrIsTerminal());
    std::vector<std::string> summaries(names.size());
    const bool batch = names.size() > 1;
    const int code = runJobs(
        names.size(), threads,
        [&](std::size_t job)
        {
            const JobResult result = work(job, [&](const std::string& text) { board.update(job, text); });
            summaries[job] = result.summary;
            if (batch || result.exitCode != 0)
            {
                board.finish(job, result.exitCode == 0 ? "done"
                                                       : "FAILED (exit " + std::to_string(result.exitCode) +
                                                             "): " + result.error);
            }
            return result.exitCode;
        });
    board.close();
    if (!quiet)
    {
        for (const std::string& summary : summaries)
        {
            if (!summary.empty())
            {
                std::printf("%s\n", summary.c_str());
            }
        }
    }
    return code;
}

} // namespace frontier::app
