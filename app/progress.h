// app/progress.h: a one-line progress display on stderr, only when stderr is a terminal.
#pragma once

#include <chrono>

namespace frontier::app
{

class ProgressLine
{
  public:
    ProgressLine(bool enabled, long totalSteps, double dt);
    void update(long step);
    void finish();

  private:
    bool mEnabled;
    long mTotal;
    double mDt;
    std::chrono::steady_clock::time_point mLast;
    bool mShown = false;
};

bool stderrIsTerminal();

} // namespace frontier::app
