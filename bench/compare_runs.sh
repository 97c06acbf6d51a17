#!/usr/bin/env bash
# False-alarm and detection figures of `aoreplay compare` from real runs on one device.
# For each of PAIRS rounds it runs the same build three times, interleaved: A and B with the same
# settings, S with one extra GTAO slice (a real slowdown). compare A B should say `same` (no exit 1);
# compare A S should say `slower` (exit 1).
#   bash bench/compare_runs.sh BUILD_DIR OUT_DIR [PAIRS=20] [extra `aoreplay run` args...]
# The extra `aoreplay run` args go to all three runs (e.g. `--preset ultra`, `--set slices=2`). S
# adds `--set slices=N+1`, where N is the slice count A's report.json says A ran with (3 with the
# default preset, high), so S is one slice more than A whatever the preset or settings.
# COMPARE_ARGS (words split on spaces) go to `aoreplay compare`, e.g.
#   COMPARE_ARGS='--judge-host-copies'   to let the upload and read-back copies fail it too.
# "every pass 'same'" counts the names compare judges.
# REJUDGE=1 runs nothing: it judges the runs already in OUT_DIR again with BUILD_DIR's `compare`
# (to see what a change to the verdict rules does to earlier experiments).
set -euo pipefail
build=${1:?build dir}
out=${2:?output dir}
pairs=${3:-20}
shift $(( $# < 3 ? $# : 3 ))
aoreplay="$build/replay/aoreplay"
capture="$(dirname "$0")/../captures/boxes-orbit"
run_args=(--frames 0:4 --repeat 10 --warmup 2 --no-images "$@")
read -ra compare_args <<< "${COMPARE_ARGS:-}"
mkdir -p "$out"

replay() {  # name, extra settings...
  local name=$1; shift
  "$aoreplay" run "$capture" "${run_args[@]}" "$@" --out "$out/$name" >/dev/null
}

report_slices() {  # report.json -> the GTAO slice count the run used
  python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['settings']['slices'])" "$1"
}

false_alarms=0 all_same=0 detected=0
for i in $(seq 1 "$pairs"); do
  if [ -z "${REJUDGE:-}" ]; then
    replay "a$i"
    replay "b$i"
    replay "s$i" --set slices=$(($(report_slices "$out/a$i/report.json") + 1))
  fi
  slices=$(report_slices "$out/a$i/report.json")
  s_slices=$(report_slices "$out/s$i/report.json")
  if [ "$s_slices" -ne $((slices + 1)) ]; then
    echo "compare_runs.sh: S ran with $s_slices slices, expected $((slices + 1)) (A ran with $slices)" >&2
    exit 2
  fi
  set +e
  "$aoreplay" compare "$out/a$i/report.json" "$out/b$i/report.json" "${compare_args[@]}" --json "$out/same$i.json" >"$out/same$i.txt"
  same_rc=$?
  "$aoreplay" compare "$out/a$i/report.json" "$out/s$i/report.json" "${compare_args[@]}" --json "$out/slow$i.json" >"$out/slow$i.txt"
  slow_rc=$?
  set -e
  [ "$same_rc" -eq 1 ] && false_alarms=$((false_alarms + 1))
  [ "$slow_rc" -eq 1 ] && detected=$((detected + 1))
  python3 -c "import json,sys; d=json.load(open(sys.argv[1])); sys.exit(any(p['verdict']!='same' for p in d['passes'] if p.get('judged', True)))" \
    "$out/same$i.json" && all_same=$((all_same + 1))
  total_same=$(python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(next(p['verdict'] for p in d['passes'] if p['name']=='total'))" "$out/same$i.json")
  total_slow=$(python3 -c "import json,sys; d=json.load(open(sys.argv[1])); p=next(p for p in d['passes'] if p['name']=='total'); print(p['verdict'], 'x%.3f' % p['ratio'])" "$out/slow$i.json")
  echo "pair $i: A vs B exit $same_rc (total: $total_same); A vs slices=$s_slices exit $slow_rc (total: $total_slow)"
done
echo "same build, separate runs: every pass 'same' in $all_same/$pairs; exit 1 (slowdown claimed) in $false_alarms/$pairs"
echo "one extra slice: $detected/$pairs called slower"
