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
# One small capture per scene kind (README of replay/generator: scenes and their oracles). Few
# frames: the oracles need one view; the others enough motion to exercise history.
gen plane-static plane --size 320x180 --frames 1 --path static --reference-spp 128
gen pit-cut pit --size 320x180 --frames 4 --path cut --reference-spp 128
gen sphere-orbit sphere --size 320x180 --frames 6 --path orbit --reference-spp 128
gen bunny-orbit bunny --size 320x180 --frames 8 --path orbit --reference-spp 64
gen thin-strafe thin --size 320x180 --frames 8 --path strafe --reference-spp 64
# Temporal stability (issue "Temporal stability"): a still camera (pure flicker), a fast strafe past
# the front buildings (disocclusion) and a path with a cut; small, 16 frames each, so history has
# time to settle at the weights the tests use.
gen boxes-static boxes --size 160x90 --frames 16 --path static --reference-spp 64
gen boxes-strafe boxes --size 160x90 --frames 16 --path strafe --reference-spp 64
gen boxes-cut boxes --size 160x90 --frames 16 --path cut --reference-spp 64
# A second depth layer (issue "SAO, and deep G-buffer AO from a second depth layer"): the thin
# occluders with depth2 (depth peeling, 1 cm minimum separation), 2 frames of the strafe.
gen thin-depth2 thin --size 320x180 --frames 2 --path strafe --reference-spp 64 --depth2
# The same with a 5 cm separation, more than the 4 cm poles and 2 cm slats are thick: their second
# layer is what lies behind them rather than their back faces (replay/techniques/sao/README.md).
gen thin-depth2-5cm thin --size 320x180 --frames 2 --path strafe --reference-spp 64 --depth2 --depth2-separation 0.05
