// tests/soak.h: soak tests, long runs (up to 400 000 steps, or dense solves of many random
// systems) whose code paths shorter tests cover too. They run in the Release build; in the
// AddressSanitizer + UndefinedBehaviorSanitizer build (FRONTIER_SANITIZED, tests/CMakeLists.txt)
// they are skipped: there each took half a minute to two minutes.
#pragma once

#include <gtest/gtest.h>

#ifdef FRONTIER_SANITIZED
#define FRONTIER_SOAK_TEST()                                                                                 \
    GTEST_SKIP() << "soak test: runs in the Release build, skipped under the sanitizers"
#else
#define FRONTIER_SOAK_TEST() static_cast<void>(0)
#endif
