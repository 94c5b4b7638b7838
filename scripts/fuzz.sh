#!/usr/bin/env bash
# Fuzzes the input readers with libFuzzer under AddressSanitizer and UndefinedBehaviorSanitizer.
# Usage: scripts/fuzz.sh TARGET|all SECONDS
#   TARGET: yaml_scene (YAML scenes), urdf (URDF models), mesh (mesh files through assimp),
#   trajectory (the trajectory reader of `check` and `render`), scene_steps (a YAML scene loaded,
#   its simulation built and stepped: the whole path of `frontier run`), batch_plan (batch plans
#   and their first jobs' scenes, stepped); all: each of them for SECONDS, FUZZ_JOBS (default 2)
#   at a time.
# Builds fuzz/ in build-fuzz/ (FUZZ_BUILD_DIR) with clang (cmake -DFRONTIER_FUZZ=ON; only the io and
# core libraries and the targets), seeds build-fuzz/seeds/TARGET from scenes/ and tests/ (fuzz/seeds.sh) and
# grows build-fuzz/corpus/TARGET. An io::InputError is the readers' answer to bad input; a crash,
# a sanitizer report, a leak, an input slower than 5 s (-timeout=5; FUZZ_TIMEOUT=N raises it on a
# busy machine, where the bundled quadruped alone can take 5 s under the sanitizers) or over 2 GB of memory
# (-rss_limit_mb=2048) is a finding: its input is saved as build-fuzz/findings/TARGET-*, the log
# as build-fuzz/logs/TARGET.log, and the script exits 1. Replay one: build-fuzz/fuzz/fuzz_TARGET FILE.
# Needs clang and libclang-rt-14-dev (scripts/install-deps.sh --for-tests).
set -euo pipefail
cd "$(dirname "$0")/.."

targets=(yaml_scene urdf mesh trajectory scene_steps batch_plan)
if [[ $# -ne 2 || ! $2 =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: scripts/fuzz.sh TARGET|all SECONDS   (TARGET: ${targets[*]})" >&2
  exit 2
fi
if [[ $1 == all ]]; then
  selected=("${targets[@]}")
elif [[ " ${targets[*]} " == *" $1 "* ]]; then
  selected=("$1")
else
  echo "fuzz: unknown target '$1' (expected one of: ${targets[*]} or all)" >&2
  exit 2
fi
seconds=$2
jobs=${FUZZ_JOBS:-2}
build=${FUZZ_BUILD_DIR:-build-fuzz}

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found; run scripts/install-deps.sh --for-tests (clang, libclang-rt-14-dev)" >&2
  exit 2
fi
launcher=()
if command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# A tree already configured with FRONTIER_FUZZ=ON (build-fuzz/, or a sanitizer build made with clang,
# FUZZ_BUILD_DIR=build-sanitize) is used as it is.
if ! grep -q '^FRONTIER_FUZZ:BOOL=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DFRONTIER_FUZZ=ON \
    -DBUILD_TESTING=OFF -DFRONTIER_BENCHMARKS=OFF -DFRONTIER_WERROR=ON "${launcher[@]}" >/dev/null
fi
cmake --build "$build" -j"${JOBS:-2}" --target "${selected[@]/#/fuzz_}"
fuzz/seeds.sh "$build/seeds"

mkdir -p "$build/findings" "$build/logs"
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# scene_steps reads what yaml_scene reads: the same words.
declare -A dictionary=([scene_steps]=yaml_scene)

# One target for `seconds`; its exit status.
# The target writes each input to a file under TMPDIR (fuzz/fuzz_input.h): a folder of the build's,
# emptied first, so a crashed run leaves nothing in /tmp.
run_one() {
  local t=$1
  mkdir -p "$build/corpus/$t"
  rm -rf "$build/tmp/$t" && mkdir -p "$build/tmp/$t"
  TMPDIR=$(cd "$build/tmp/$t" && pwd) "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout="${FUZZ_TIMEOUT:-5}" -rss_limit_mb=2048 -max_len=65536 \
    -dict="fuzz/${dictionary[$t]:-$t}.dict" -artifact_prefix="$build/findings/$t-" -print_final_stats=1 \
    "$build/corpus/$t" "$build/seeds/$t" >"$build/logs/$t.log" 2>&1
}

failed=()
pids=()
names=()
wait_one() {
  local i=$1
  if wait "${pids[$i]}"; then
    echo "fuzz: ${names[$i]}: no finding in ${seconds} s ($(grep -o 'stat::number_of_executed_units: [0-9]*' \
      "$build/logs/${names[$i]}.log" | grep -o '[0-9]*$' || echo '?') inputs)"
  else
    echo "fuzz: ${names[$i]}: FINDING, see $build/logs/${names[$i]}.log and $build/findings/${names[$i]}-*" >&2
    grep -m3 -E 'ERROR|SUMMARY|Test unit written' "$build/logs/${names[$i]}.log" >&2 || true
    failed+=("${names[$i]}")
  fi
}
for t in "${selected[@]}"; do
  if [[ ${#pids[@]} -ge $jobs ]]; then
    wait_one 0
    pids=("${pids[@]:1}")
    names=("${names[@]:1}")
  fi
  run_one "$t" &
  pids+=($!)
  names+=("$t")
done
while [[ ${#pids[@]} -gt 0 ]]; do
  wait_one 0
  pids=("${pids[@]:1}")
  names=("${names[@]:1}")
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "fuzz: findings in ${failed[*]}" >&2
  exit 1
fi
