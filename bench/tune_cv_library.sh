#!/usr/bin/env bash
# Issue 54's experiment: every built-in technique with tunable keys cross-validated on a training
# library (captures/library.sh), then the table and the plot of held-out RMSE against GPU time,
# each technique at its defaults and tuned (bench/tune_cv_summary.py).
# Usage: bash bench/tune_cv_library.sh AOREPLAY LIBRARY OUT [MAX_EVALUATIONS] [TECHNIQUES...]
set -uo pipefail
aoreplay=$1 library=$2 out=$3 evaluations=${4:-30}
shift $(( $# < 4 ? $# : 4 ))
techniques=("$@")
((${#techniques[@]})) || techniques=(gtao xegtao vbao cacao sao rtao)
mkdir -p "$out"
for t in "${techniques[@]}"; do
  rm -rf "$out/$t"
  "$aoreplay" tune "$library" --technique "$t" --cv --max-evaluations "$evaluations" --out "$out/$t" > "$out/$t.log" 2>&1
  echo "$t: exit $? ($(grep -c '^\[' "$out/$t.log") evaluations)"
done
python3 "$(dirname "$0")/tune_cv_summary.py" "$out" "${techniques[@]}"
