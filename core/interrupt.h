// core/interrupt.h: SIGINT, SIGTERM and SIGHUP as a request to stop (README "Exit codes"). The
// handlers set a flag instead of killing the process; the step loop reads it between steps and
// loading (meshes, hulls, links) at its checkpoints, so that a command stops promptly, removes its
// temporary files and exits with 128 + the signal.
#pragma once

#include <stdexcept>
#include <string>

namespace frontier::core
{

// Installed by the commands that read the flag (run, render, check, batch).
void installInterruptHandlers();
// The signal received since installInterruptHandlers, 0: none.
int interruptSignal();
// "SIGINT", "SIGTERM", "SIGHUP".
std::string signalName(int signal);
// The exit code of a process stopped by `signal`: 128 + its number (130, 143, 129).
inline int interruptedExitCode(int signal)
{
    return 128 + signal;
}

// Thrown at a checkpoint of work outside the step loop (loading a scene) once a signal has come:
// what() is "interrupted by SIGTERM".
class Interrupted : public std::runtime_error
{
  public:
    explicit Interrupted(int signal);
    int signal() const { return mSignal; }

  private:
    int mSignal;
};

// A checkpoint: throws Interrupted when a signal has come since installInterruptHandlers.
void throwIfInterrupted();

} // namespace frontier::core
