// app/progress.cpp: progress line on a terminal, redrawn at most ten times a second.
#include "app/progress.h"

#include <cstdio>
#include <unistd.h>

namespace frontier::app
{

bool stderrIsTerminal()
{
    return isatty(fileno(stderr)) != 0;
}

ProgressLine::ProgressLine(bool enabled, long totalSteps, double dt)
    : mEnabled(enabled), mTotal(totalSteps), mDt(dt), mLast(std::chrono::steady_clock::now())
{
}

void ProgressLine::update(long step)
{
    if (!mEnabled)
    {
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (now - mLast < std::chrono::milliseconds(100) && step != mTotal)
    {
        return;
    }
    mLast = now;
    const double percent =
        mTotal > 0 ? 100.0 * static_cast<double>(step) / static_cast<double>(mTotal) : 100.0;
    std::fprintf(stderr, "\r[%5.1f%%] t = %.3f / %.3f s, step %ld / %ld", percent,
                 static_cast<double>(step) * mDt, static_cast<double>(mTotal) * mDt, step, mTotal);
    std::fflush(stderr);
    mShown = true;
}

void ProgressLine::finish()
{
    if (mShown)
    {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
}

} // namespace frontier::app
