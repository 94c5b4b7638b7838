#!/usr/bin/env bash
# Builds and runs the whole test suite: a Release build (g++, warnings are errors) and an
# AddressSanitizer + UndefinedBehaviorSanitizer build (clang) of the tests and the fuzz targets,
# each run with ctest -j2; then each fuzz target (fuzz/) for FUZZ_SECONDS (default 20, 0 skips),
# two at a time, from that same build.
# Installs missing Debian packages first (scripts/install-deps.sh --for-tests --with-peers); the
# Release build also builds and tests bench/peers (the comparison with Bullet, ODE and MuJoCo).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-2}

scripts/install-deps.sh --for-tests --with-peers

echo "== Release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DFRONTIER_WERROR=ON -DFRONTIER_PEERS=ON >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build -j"$jobs" --output-on-failure

echo "== Sanitizer build (clang; address, undefined; tests and fuzz targets) and tests"
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DFRONTIER_SANITIZE=ON \
  -DFRONTIER_FUZZ=ON -DFRONTIER_BENCHMARKS=OFF -DFRONTIER_WERROR=ON >/dev/null
cmake --build build-sanitize -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build-sanitize -j"$jobs" --output-on-failure

fuzz_seconds=${FUZZ_SECONDS:-20}
if [[ $fuzz_seconds -gt 0 ]]; then
  echo "== Fuzz targets (libFuzzer, address, undefined): ${fuzz_seconds} s each"
  FUZZ_BUILD_DIR=build-sanitize JOBS=$jobs FUZZ_JOBS=2 scripts/fuzz.sh all "$fuzz_seconds"
fi

