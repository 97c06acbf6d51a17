#!/usr/bin/env bash
# bench/ab_experiments.sh against a stand-in `aoreplay` (no GPU, nothing timed): its `ab` records
# the side arguments it got and writes a compare.json whose verdicts follow them (slices=4 on B:
# gtao and total slower, exit 1; ultra on A: gtao faster; else every name same). Checks that each
# kind passes the arguments the issue names, that the summary counts what the runs said, and that
# the hog experiments leave no hog behind.
#   bash tests/scripts/ab_experiments_test.sh SCRATCH_DIR
set -euo pipefail
script="$(cd "$(dirname "$0")/../.." && pwd)/bench/ab_experiments.sh"
scratch=${1:?scratch dir}
rm -rf "$scratch"
mkdir -p "$scratch/build/replay"
cat > "$scratch/build/replay/aoreplay" <<'STUB'
#!/usr/bin/env bash
[ "$1" = ab ] || exit 9
a= b= out=
while [ $# -gt 0 ]; do
  case $1 in --a) a=$2; shift;; --b) b=$2; shift;; --out) out=$2; shift;; esac
  shift
done
mkdir -p "$out"
printf 'a=%s\nb=%s\n' "$a" "$b" > "$out/args.txt"
gtao=same total=same rc=0
case $b in *"--set slices=4"*) gtao=slower total=slower rc=1;; esac
case $a in *"--preset ultra"*) gtao=faster;; esac
cat > "$out/compare.json" <<JSON
{"passes": [{"name": "gtao", "verdict": "$gtao", "judged": true, "ratio": 1.0},
            {"name": "total", "verdict": "$total", "judged": true, "ratio": 1.0},
            {"name": "upload", "verdict": "slower", "judged": false, "ratio": 1.0}]}
JSON
sleep 0.2
exit $rc
STUB
chmod +x "$scratch/build/replay/aoreplay"

failures=0
fail() { echo "FAIL $*"; failures=$((failures + 1)); }
out="$scratch/out"
tag="ab-experiments-test-hog-$$"  # this test's hogs only: another experiment may run beside it
log=$(HOG_TAG=$tag RUN_ARGS="--frames 0:2" bash "$script" "$scratch/build" "$out" 2 1 2>&1) || fail "the script failed: $log"
grep -qx "a=--frames 0:2 --preset ultra" "$out/preset/1/args.txt" || fail "preset A args: $(cat "$out/preset/1/args.txt")"
grep -qx "b=--frames 0:2 --preset high" "$out/preset/1/args.txt" || fail "preset B args: $(cat "$out/preset/1/args.txt")"
grep -qx "b=--frames 0:2 --set slices=4" "$out/slice/2/args.txt" || fail "slice B args: $(cat "$out/slice/2/args.txt")"
grep -qx "b=--frames 0:2 " "$out/same/1/args.txt" || fail "same B args: $(cat "$out/same/1/args.txt")"
summary="$out/summary.json"
check() {  # python expression on the summary, description
  python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['kinds']; sys.exit(0 if ($1) else 1)" "$summary" || fail "$2: $(cat "$out/summary.txt")"
}
check "s['same']['exit_codes'] == {'0': 2} and s['same']['every_judged_name_same'] == 2" "same"
check "s['hog']['exit_codes'] == {'0': 2} and s['hog']['every_judged_name_same'] == 2" "hog"
check "s['slice']['exit_codes'] == {'1': 2} and s['slice']['gtao_verdicts'] == {'slower': 2}" "slice"
check "s['preset']['gtao_verdicts'] == {'faster': 2} and s['preset']['every_judged_name_same'] == 0" "preset"
grep -q "hog 2: exit 0 .*one busy core from" <<< "$log" || fail "no hog note: $log"
# The hog was started by the script as `timeout ... bash -c 'while :; do :; done' TAG`; none may outlive it.
if pgrep -f "while :; do :; done $tag" >/dev/null; then fail "a hog outlived the script"; fi
[ "$failures" -eq 0 ] && echo "ok: arguments per kind, summary counts, no hog left"
[ "$failures" -eq 0 ]
