#!/usr/bin/env bash
# How long loading a capture of 10^5 frames takes (issue 20: linear, under 10 s), and how fast one
# past the frame limit (100 000) is refused (under 1 s), through `aoreplay graph` (which loads the
# capture, checks every EXR header, and needs no GPU). capture.json is written as writeCapture
# writes it (pretty-printed, about 1 KB a frame); the frames name:
#   cycled     the 24 G-buffers and references of captures/boxes-orbit, in turn (each file checked once)
#   distinct   100 000 distinct file names (hard links to those 24 files: every name resolved and checked)
# Usage: bench/capture_load.sh [AOREPLAY=build/replay/aoreplay] [WORK=/tmp/aor-capture-load]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
aoreplay=${1:-$root/build/replay/aoreplay}
work=${2:-/tmp/aor-capture-load}
rm -rf "$work" && mkdir -p "$work"
python3 - "$root/captures/boxes-orbit" "$work" <<'PY'
import json, os, sys
source, work = sys.argv[1], sys.argv[2]
base = json.load(open(os.path.join(source, "capture.json")))
def capture(name, count, distinct):
    folder = os.path.join(work, name)
    os.makedirs(os.path.join(folder, "frames"))
    frames = []
    for i in range(count):
        f = dict(base["frames"][i % len(base["frames"])])
        for key in ("gbuffer", "reference"):
            original = os.path.join(source, f[key])
            target = f[key] if not distinct else "frames/%06d%s" % (i, ".ref.exr" if key == "reference" else ".exr")
            if not os.path.exists(os.path.join(folder, target)):
                os.link(original, os.path.join(folder, target))
            f[key] = target
        frames.append(f)
    doc = dict(base, frames=frames)
    with open(os.path.join(folder, "capture.json"), "w") as out:
        out.write(json.dumps(doc, indent=2) + "\n")
capture("cycled-100000", 100000, False)
capture("cycled-100001", 100001, False)
capture("distinct-100000", 100000, True)
PY
# Wall time and the process's CPU time (user + system, both threads): on a shared machine the wall
# time follows the load, the CPU time much less.
TIMEFORMAT='%R %U %S'
for name in cycled-100000 distinct-100000 cycled-100001; do
  size=$(stat -c %s "$work/$name/capture.json")
  set +e
  times=$( { time "$aoreplay" graph "$work/$name" --frames 0:1 --dot - > /dev/null 2> "$work/$name.err"; echo "exit $?" > "$work/$name.rc"; } 2>&1 )
  set -e
  read -r wall user sys <<< "$times"
  printf '%-16s capture.json %4d MB  %s  wall %6.2f s  cpu %6.2f s  %s\n' "$name" $((size / 1000000)) \
    "$(cat "$work/$name.rc")" "$wall" "$(awk "BEGIN {print $user + $sys}")" "$(head -c 110 "$work/$name.err")"
done
rm -rf "$work"
