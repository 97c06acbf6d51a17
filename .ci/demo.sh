#!/usr/bin/env bash
# README command 1: set up, build, and replay the default shipped capture on lavapipe.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
./build/replay/aoreplay run captures/boxes-orbit "$@"
