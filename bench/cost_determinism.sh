#!/usr/bin/env bash
# Counted cost is exact: every built-in technique but `reference` at its default preset, N
# separate processes each for instructions and cycles, every pass and frame compared.
# Usage: bench/cost_determinism.sh AOREPLAY CAPTURE FRAMES WORK [N] [TECHNIQUES...]
# Environment: MEASURES (default "instructions cycles").
# Prints one line per technique and measure: identical, or the largest spread between the
# processes of one pass and frame (absolute and relative) and of the run's total; exits 1 when any
# differs. Each run is a whole `aoreplay run --cost ...` process (its own valgrind).
set -euo pipefail
aoreplay=$1 capture=$2 frames=$3 work=$4 n=${5:-5}
shift $(( $# < 5 ? $# : 5 ))
techniques=("$@")
((${#techniques[@]})) || techniques=(gtao xegtao cacao sao rtao)
mkdir -p "$work"
status=0
for technique in "${techniques[@]}"; do
  for measure in ${MEASURES:-instructions cycles}; do
    for i in $(seq 1 "$n"); do
      out="$work/$technique-$measure-$i"
      rm -rf "$out"
      /usr/bin/time -f "%e s wall, %U+%S s CPU" -o "$out.time" \
        "$aoreplay" run "$capture" --technique "$technique" --frames "$frames" --cost "$measure" --no-images \
        --out "$out" > "$out.log" 2>&1
    done
    python3 - "$work" "$technique" "$measure" "$n" <<'PY' || status=1
import json, sys
work, technique, measure, n = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
runs = [json.load(open(f"{work}/{technique}-{measure}-{i}/report.json")) for i in range(1, n + 1)]
def values(r):
    return {(f["index"], name): v for f in r["frames"] for name, v in f[measure].items()}
all_values = [values(r) for r in runs]
first = all_values[0]
times = [open(f"{work}/{technique}-{measure}-{i}.time").read().strip() for i in range(1, n + 1)]
total = runs[0][measure + "_total"]
if all(v == first for v in all_values):
    print(f"{technique} {measure}: identical in {n} processes ({len(first)} pass-frames, total {total:.0f}); {times[0]}")
    sys.exit(0)
worst = max(((max(v[k] for v in all_values) - min(v[k] for v in all_values)) / min(v[k] for v in all_values), k,
             max(v[k] for v in all_values) - min(v[k] for v in all_values)) for k in first)
totals = [r[measure + "_total"] for r in runs]
print(f"{technique} {measure}: NOT identical in {n} processes: largest spread {worst[2]:.0f} ({worst[0]:.1e}) at frame "
      f"{worst[1][0]} pass {worst[1][1]}; total spread {(max(totals) - min(totals)) / min(totals):.1e}; {times[0]}")
sys.exit(1)
PY
  done
done
exit $status
