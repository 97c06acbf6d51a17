#!/usr/bin/env bash
# Builds the capture-reader fuzzer with clang (libFuzzer + ASan + UBSan) and runs it for a bounded
# time: tests/fuzz/run_fuzzer.sh [SECONDS=60] [BUILD_DIR=build-fuzz]
# Inputs that crash are written to tests/fuzz/regression/ (add them to git: the regular test suite
# replays that folder); the exit status is non-zero when the fuzzer found one.
# Needs the Debian packages clang and libclang-rt-14-dev (libFuzzer's runtime).
set -euo pipefail
seconds=${1:-60}
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${2:-$root/build-fuzz}
fuzz=$root/tests/fuzz
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DAOREPLAY_BUILD_FUZZER=ON \
  -DAOREPLAY_BUILD_TESTS=OFF -DAOREPLAY_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --target capture_reader_fuzzer -j"${JOBS:-1}"
work=$build/fuzz-corpus  # grows while fuzzing; the committed seeds stay small
mkdir -p "$work" "$fuzz/regression"
# Single process; -rss_limit_mb also caps single allocations, so a header that makes the reader
# allocate more than that is reported as a finding instead of swapping the machine.
"$build/tests/fuzz/capture_reader_fuzzer" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=20 \
  -dict="$fuzz/capture.dict" -artifact_prefix="$fuzz/regression/" -print_final_stats=1 \
  "$work" "$fuzz/corpus"
