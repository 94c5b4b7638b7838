// tests/soak.h: soak tests, long runs (up to 400 000 steps, or dense solves of many random
// systems) whose code paths shorter tests cover too. They run in the Release build; in the
// AddressSanitizer + UndefinedBehaviorSanitizer build (FRONTIER_SANITIZED, tests/CMakeLists.txt)
// they are skipped (FRONTIER_SOAK_TEST) or run shorter (soakSeconds): there each took half a minute
// to two minutes.
#pragma once

#include <gtest/gtest.h>

#ifdef FRONTIER_SANITIZED
#define FRONTIER_SOAK_TEST()                                                                                 \
    GTEST_SKIP() << "soak test: runs in the Release build, skipped under the sanitizers"
#else
#define FRONTIER_SOAK_TEST() static_cast<void>(0)
#endif

// A soak run's simulated length (s): `release` in the Release build; under the sanitizers
// `sanitized`, long enough to run the same code (solvers, contacts) over many steps. The bounds
// checked are the Release run's, over the shorter run.
constexpr double soakSeconds([[maybe_unused]] double release, [[maybe_unused]] double sanitized)
{
#ifdef FRONTIER_SANITIZED
    return sanitized;
#else
    return release;
#endif
}
