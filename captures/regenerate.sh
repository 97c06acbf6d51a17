#!/usr/bin/env bash
# Regenerates every shipped capture with the project's own generator (deterministic: the same
# build writes byte-identical files). Usage: bash captures/regenerate.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build}/replay/aoreplay"
[ -x "$exe" ] || { echo "build first (bash .ci/build.sh): $exe not found" >&2; exit 2; }
gen() {
  local name=$1
  shift
  "$exe" capture "$@" --out "captures/$name"
}
# Default capture: a city block of boxes, slow orbit, ray-traced reference.
gen boxes-orbit boxes --size 320x180 --frames 24 --path orbit --reference-spp 64
