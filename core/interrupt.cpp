// core/interrupt.cpp: the interrupt flag and its signal handlers.
#include "core/interrupt.h"

#include <csignal>

namespace frontier::core
{

namespace
{
volatile std::sig_atomic_t gSignal = 0;

extern "C" void onInterrupt(int signal)
{
    gSignal = signal;
}
} // namespace

void installInterruptHandlers()
{
    struct sigaction action
    {
    };
    action.sa_handler = onInterrupt;
    sigemptyset(&action.sa_mask);
    for (int signal : {SIGINT, SIGTERM, SIGHUP})
    {
        sigaction(signal, &action, nullptr);
    }
}

int interruptSignal()
{
    return gSignal;
}

std::string signalName(int signal)
{
    switch (signal)
    {
    case SIGINT:
        return "SIGINT";
    case SIGTERM:
        return "SIGTERM";
    case SIGHUP:
        return "SIGHUP";
    default:
        return "signal " + std::to_string(signal);
    }
}

Interrupted::Interrupted(int signal)
    : std::runtime_error("interrupted by " + signalName(signal)), mSignal(signal)
{
}

void throwIfInterrupted()
{
    if (const int signal = interruptSignal(); signal != 0)
    {
        throw Interrupted(signal);
    }
}

} // namespace frontier::core
