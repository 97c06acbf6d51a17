#!/usr/bin/env bash
# Issue 19 (bench/RESULTS.md): N interleaved pairs of `run captures/boxes-orbit --frames 0:6` with no flags
# against `--warmup 5 --repeat 5 --no-images`; per pair the ratio of gtao's median and of the total.
# bash bench/warmup_pairs.sh BUILD/replay/aoreplay [N=10] [OUT=/tmp/pairs], from the repository root.
set -euo pipefail
BIN=$1 N=${2:-10} OUT=${3:-/tmp/pairs}
rm -rf "$OUT"; mkdir -p "$OUT"
for i in $(seq 1 "$N"); do
  "$BIN" run captures/boxes-orbit --frames 0:6 --out "$OUT/d$i" > /dev/null 2>&1
  "$BIN" run captures/boxes-orbit --frames 0:6 --warmup 5 --repeat 5 --no-images --out "$OUT/w$i" > /dev/null 2>&1
done
python3 - "$OUT" "$N" <<'PY'
import json, statistics, sys
out, n = sys.argv[1], int(sys.argv[2])
def pick(path):
    r = json.load(open(path))
    gtao = next(p for p in r["passes"] if p["name"] == "gtao")["gpu_ms"]["median"]
    return gtao, r["gpu_ms_total_median"], r.get("timing", {}).get("mode")
g, t = [], []
for i in range(1, n + 1):
    dg, dt, mode = pick(f"{out}/d{i}/report.json"); wg, wt, _ = pick(f"{out}/w{i}/report.json")
    g.append(dg / wg); t.append(dt / wt)
    print(f"pair {i}: default gtao {dg:.3f} total {dt:.3f} ({mode}) | warm gtao {wg:.3f} total {wt:.3f}")
print(f"median ratio default/warm: gtao {statistics.median(g):.3f}, total {statistics.median(t):.3f}")
PY
