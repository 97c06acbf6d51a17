#!/usr/bin/env bash
# Builds a JSON-reader fuzzer with clang (libFuzzer + ASan + UBSan) and runs it for a bounded time:
#   tests/fuzz/run_fuzzer.sh [SECONDS=60] [BUILD_DIR=build-fuzz] [TARGET=capture_reader]
# TARGET: capture_reader (capture.json + EXR), expectations (--expect), timing_json (compare's
# report.json / Google Benchmark JSON), technique_spec (a user technique's technique.json),
# settings_file (--settings). Inputs that crash are written to the target's regression
# folder (add them to git: the regular test suite replays it); the exit status is non-zero when the
# fuzzer found one. Needs the Debian packages clang and libclang-rt-14-dev (libFuzzer's runtime).
set -euo pipefail
seconds=${1:-60}
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${2:-$root/build-fuzz}
target=${3:-capture_reader}
fuzz=$root/tests/fuzz
case $target in
  capture_reader) corpus=$fuzz/corpus regression=$fuzz/regression dict=(-dict="$fuzz/capture.dict") ;;
  expectations) corpus=$fuzz/corpus-expectations regression=$fuzz/regression-expectations dict=(-dict="$fuzz/json.dict") ;;
  timing_json) corpus=$fuzz/corpus-timing regression=$fuzz/regression-timing dict=(-dict="$fuzz/json.dict") ;;
  technique_spec) corpus=$fuzz/corpus-technique regression=$fuzz/regression-technique dict=(-dict="$fuzz/technique.dict") ;;
  settings_file) corpus=$fuzz/corpus-settings regression=$fuzz/regression-settings dict=(-dict="$fuzz/settings.dict") ;;
  *) echo "unknown target $target (capture_reader, expectations, timing_json, technique_spec, settings_file)" >&2; exit 2 ;;
esac
mkdir -p "$build"
# Several targets may be run at once (CTest -j): one configures and builds, the others wait.
(
  flock 9
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAOREPLAY_BUILD_FUZZER=ON \
    -DAOREPLAY_BUILD_TESTS=OFF -DAOREPLAY_BUILD_BENCH=OFF >/dev/null
  cmake --build "$build" --target "${target}_fuzzer" -j"${JOBS:-1}"
) 9>"$build/.build-lock"
work=$build/fuzz-corpus-$target  # grows while fuzzing; the committed seeds stay small
mkdir -p "$work" "$regression"
# Single process; -rss_limit_mb also caps single allocations, so an input that makes a reader
# allocate more than that is reported as a finding instead of swapping the machine.
"$build/tests/fuzz/${target}_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 \
  "${dict[@]}" -artifact_prefix="$regression/" -print_final_stats=1 "$work" "$corpus"
