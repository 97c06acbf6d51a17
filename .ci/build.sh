#!/usr/bin/env bash
# Installs missing Debian packages and builds aoreplay, its tests and benchmarks into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j"$(nproc)"
