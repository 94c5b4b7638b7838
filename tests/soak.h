// tests/soak.h: soak tests, long physics runs (hundreds of thousands of steps, or solves of
// hundreds of random systems) whose code paths the shorter tests cover too. They run in the
// Release build; in the AddressSanitizer + UndefinedBehaviorSanitizer build (FRONTIER_SANITIZED,
// tests/CMakeLists.txt) they are skipped, where they would take minutes each.
#pragma once

#include <gtest/gtest.h>

#ifdef FRONTIER_SANITIZED
#define FRONTIER_SOAK_TEST()                                                                                 \
    GTEST_SKIP() << "soak test: runs in the Release build, skipped under the sanitizers"
#else
#define FRONTIER_SOAK_TEST() static_cast<void>(0)
#endif
