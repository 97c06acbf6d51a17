#!/usr/bin/env bash
# bench/compare_runs.sh gives its S run one GTAO slice more than A ran with, whatever preset or
# --set the extra run args choose. Runs the script against a stand-in `aoreplay` (no GPU, no
# timing): `run` records its arguments and writes a report.json whose settings.slices follows
# --preset (low 1, medium 2, high 3, ultra 9, as replay/replay_loop/settings.cpp) and the last
# --set slices=N; `compare` writes a `same` verdict. Also: REJUDGE=1 replays nothing.
#   bash tests/scripts/compare_runs_test.sh SCRATCH_DIR
set -euo pipefail
script="$(cd "$(dirname "$0")/../.." && pwd)/bench/compare_runs.sh"
scratch=${1:?scratch dir}
rm -rf "$scratch"
mkdir -p "$scratch/build/replay"
cat > "$scratch/build/replay/aoreplay" <<'STUB'
#!/usr/bin/env bash
command=$1; shift
if [ "$command" = run ]; then
  slices=3 out=
  all=("$@")
  while [ $# -gt 0 ]; do
    case $1 in
      --preset) case $2 in low) slices=1;; medium) slices=2;; high) slices=3;; ultra) slices=9;; esac; shift;;
      --set) case $2 in slices=*) slices=${2#slices=};; esac; shift;;
      --out) out=$2; shift;;
    esac
    shift
  done
  mkdir -p "$out"
  printf '%s\n' "${all[@]}" > "$out/args.txt"
  echo "{\"settings\": {\"slices\": $slices}}" > "$out/report.json"
else
  json=
  while [ $# -gt 0 ]; do [ "$1" = --json ] && json=$2; shift; done
  echo '{"passes": [{"name": "total", "verdict": "same", "ratio": 1.0}]}' > "$json"
fi
STUB
chmod +x "$scratch/build/replay/aoreplay"

slices_of() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['settings']['slices'])" "$1"; }
failures=0
check() {  # name, expected A slices, extra run args...
  local name=$1 expect=$2; shift 2
  local out="$scratch/$name" log before=$failures
  log=$(bash "$script" "$scratch/build" "$out" 2 "$@" 2>&1) || { echo "FAIL $name: the script failed: $log"; failures=$((failures + 1)); return; }
  for i in 1 2; do
    local a b s
    a=$(slices_of "$out/a$i/report.json") b=$(slices_of "$out/b$i/report.json") s=$(slices_of "$out/s$i/report.json")
    if [ "$a" != "$expect" ] || [ "$b" != "$a" ] || [ "$s" != $((a + 1)) ]; then
      echo "FAIL $name, pair $i: A $a, B $b, S $s slices (want A = B = $expect, S = $((expect + 1))); S ran with: $(tr '\n' ' ' < "$out/s$i/args.txt")"
      failures=$((failures + 1))
    fi
  done
  grep -q "A vs slices=$((expect + 1)) exit" <<< "$log" || { echo "FAIL $name: output does not name slices=$((expect + 1)): $log"; failures=$((failures + 1)); }
  [ "$failures" -eq "$before" ] && echo "ok $name: A $expect slices, S $((expect + 1))"
}
check default 3
check preset_low 1 --preset low
check preset_ultra 9 --preset ultra
check set_slices 6 --set slices=6
check preset_and_set 2 --preset ultra --set slices=2

# REJUDGE=1 judges the runs already there and replays nothing.
rm "$scratch/default/"[abs]1/args.txt
if log=$(REJUDGE=1 bash "$script" "$scratch/build" "$scratch/default" 2 2>&1) &&
   grep -q "A vs slices=4 exit" <<< "$log" && ! ls "$scratch/default/"[abs]1/args.txt >/dev/null 2>&1; then
  echo "ok rejudge: judged again, nothing replayed"
else
  echo "FAIL rejudge: $log"; failures=$((failures + 1))
fi
[ "$failures" -eq 0 ]
