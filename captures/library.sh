#!/usr/bin/env bash
# Generates a training library for `aoreplay tune` (docs/tuning.md): one capture with ray-traced
# references per scene kind and camera path of the generator, and the boxes and thin occluders at
# other AO radii, so that a fit has distinct scenes to generalise over (`tune LIBRARY --cv`).
# Usage: bash captures/library.sh OUT [WxH] [FRAMES] [REFERENCE_SPP] [BUILD]
#   defaults 96x54, 2 frames, 32 rays a pixel (what the tests use); bench/ uses 320x180, 4, 64.
# Deterministic: the same build writes byte-identical captures.
set -euo pipefail
out=${1:?usage: bash captures/library.sh OUT [WxH] [FRAMES] [REFERENCE_SPP] [BUILD]}
size=${2:-96x54} frames=${3:-2} spp=${4:-32} build=${5:-build}
exe="$(cd "$(dirname "$0")/.." && pwd)/$build/replay/aoreplay"
[ -x "$exe" ] || { echo "build first (bash .ci/build.sh): $exe not found" >&2; exit 2; }
mkdir -p "$out"
gen() {
  local name=$1
  shift
  "$exe" capture "$@" --size "$size" --frames "$frames" --reference-spp "$spp" --out "$out/$name"
}
gen boxes-orbit boxes --path orbit
gen boxes-strafe boxes --path strafe
gen boxes-cut boxes --path cut
gen boxes-orbit-r0.5 boxes --path orbit --radius 0.5
gen boxes-orbit-r2 boxes --path orbit --radius 2
gen bunny-orbit bunny --path orbit
gen sphere-orbit sphere --path orbit
gen thin-strafe thin --path strafe
gen thin-strafe-r0.5 thin --path strafe --radius 0.5
gen pit-cut pit --path cut
gen plane-static plane --path static
echo "library: $out ($(ls "$out" | wc -l) captures, $size, $frames frames, $spp rays a pixel)"
