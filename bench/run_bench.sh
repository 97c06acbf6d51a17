#!/usr/bin/env bash
# Runs ao_bench and the naive baseline (../shared/bench-baseline, built into BUILD_DIR/bench-baseline)
# in one go on the same device, then prints the pipeline next to the baseline's single pass.
#   bash bench/run_bench.sh BUILD_DIR OUT_DIR [--sizes=WxH,...] [--reps=N] [other ao_bench flags]
# Outputs: OUT_DIR/ao_bench.json (Google Benchmark JSON: compare.py and `aoreplay compare` read it),
# OUT_DIR/scaling.txt (fitted slopes), OUT_DIR/baseline-before.txt and baseline.txt, OUT_DIR/summary.md.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:?build dir}" && pwd)
out=${2:?output dir}
shift 2
mkdir -p "$out"
baseline_src=${AOR_BASELINE_DIR:-$here/../../shared/bench-baseline}
baseline="$build/bench-baseline"
if [ ! -x "$baseline/gtao" ]; then
  mkdir -p "$baseline"
  cp "$baseline_src"/* "$baseline/"
  sh "$baseline/build.sh"
fi

sizes=320x180,640x360,1920x1080 reps=10 device_index=""
for arg in "$@"; do
  case $arg in
    --sizes=*) sizes=${arg#--sizes=} ;;
    --reps=*) reps=${arg#--reps=} ;;
    --baseline-device=*) device_index=${arg#--baseline-device=} ;;
  esac
done
bench_args=()
for arg in "$@"; do [[ $arg == --baseline-device=* ]] || bench_args+=("$arg"); done

# The baseline runs before and after ao_bench: on a shared CPU (lavapipe) the load can change
# during the run, and the two figures bracket it.
run_baseline() {
  (cd "$baseline" && ./gtao --sizes "$sizes" --configs 1x2,2x2,3x3,9x3 --reps "$reps" ${device_index:+--device "$device_index"})
}
run_baseline > "$out/baseline-before.txt"
# gtao's extra rows of every earlier run: the high preset without bent normals and at half resolution.
"$build/bench/ao_bench" --sizes="$sizes" --reps="$reps" --cache="$build/bench-captures" --extra=bent=0 --extra=half_res=1 \
  "${bench_args[@]}" \
  --benchmark_out="$out/ao_bench.json" --benchmark_out_format=json --benchmark_format=console \
  --benchmark_display_aggregates_only=true 2> >(tee "$out/scaling.txt" >&2)
run_baseline | tee "$out/baseline.txt"
python3 "$here/summarize.py" "$out/ao_bench.json" "$out/baseline-before.txt" "$out/baseline.txt" | tee "$out/summary.md"
