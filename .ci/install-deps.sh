#!/usr/bin/env bash
# Installs the Debian 12 packages aoreplay needs to build, test and benchmark.
# Idempotent: installs only what is missing, so it is cheap on a prepared machine.
#
# --backports (opt-in; CI and the default device stay on bookworm's lavapipe): also adds Debian's
# bookworm-backports source and installs mesa-vulkan-drivers from it (Mesa 25.0, whose lavapipe has
# VK_KHR_ray_query and VK_KHR_acceleration_structure), which REPLACES the system's Vulkan drivers,
# bookworm's lavapipe included, for every user of the machine; the ray-query path of --technique
# rtao then runs and its tests stop skipping (replay/techniques/rtao/README.md, "The ray-query
# path", also shows how to try that lavapipe without installing it). Backports has apt priority
# 100: nothing else is upgraded from it, now or later.
set -euo pipefail
backports=0
for arg in "$@"; do
  case "$arg" in
    --backports) backports=1 ;;
    *) echo "usage: $0 [--backports]" >&2; exit 2 ;;
  esac
done
packages=(
  build-essential cmake pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-tools spirv-tools libspirv-cross-c-shared-dev
  libglm-dev libopenexr-dev nlohmann-json3-dev libcli11-dev libfmt-dev libpng-dev
  libsimdjson-dev  # bounded, linear-time JSON input (replay/capture/json_input.h)
  libre2-dev       # linear-time regular expressions for --ignore
  libnlopt-cxx-dev # derivative-free optimiser behind aoreplay tune (replay/tune/)
  libssl-dev       # SHA-256 of captures and reports (the results store's keys)
  libsqlitecpp-dev libsqlite3-dev libpqxx-dev  # aoreplay record/trend/export: the SQLite and PostgreSQL stores
  postgresql sqlite3  # the store tests: a real PostgreSQL server (and psql), the sqlite3 shell for row counts
  libshaderc-dev   # user techniques' GLSL compiled at run time (replay/techniques/user/)
  glslc            # the offline compile of a user technique's shader that FORMAT.md shows (tests/techniques/user_technique_test.cpp)
  libembree-dev libtinyobjloader-dev glmark2-data
  libgtest-dev libgmock-dev libbenchmark-dev libbenchmark-tools python3-scipy
  graphviz libgraphviz-dev  # report.html lays out the render graph with Graphviz's library
  chromium libxml2-utils     # browser test of the HTML reports (tests/browser/); xmllint checks --junit XML
  python3 python3-renderdoc librenderdoc librenderdoc-dev  # aoreplay import renderdoc; rd_scene (tests/renderdoc/)
  xvfb xauth  # vkcube under xvfb-run, captured through RenderDoc target control (tests/renderdoc/)
  mesa-utils vkd3d-demos  # glxgears and vkd3d-gears for aoreplay renderdoc-capture (tests/renderdoc/)
  godot3 qtbase5-examples  # OpenGL-core programs the import is tested on (tests/renderdoc/gl_programs_import_test.sh)
  libepoxy-dev libx11-dev libgl1-mesa-dri  # rd_gl_scene (tests/renderdoc/): GL 3.3 core through GLX and libepoxy, on llvmpipe
  clang libclang-rt-14-dev  # capture-reader fuzzer (libFuzzer), tests/fuzz/
  universal-ctags  # functions and their lengths for tests/scripts/check_function_length.py
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "installing: ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo_cmd apt-get update -qq
  $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if ((backports)); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  export DEBIAN_FRONTEND=noninteractive
  list=/etc/apt/sources.list.d/bookworm-backports.list
  if ! grep -qs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/*; then
    echo "deb http://deb.debian.org/debian bookworm-backports main" | $sudo_cmd tee "$list" >/dev/null
  fi
  $sudo_cmd apt-get update -qq
  echo "installing mesa-vulkan-drivers from bookworm-backports"
  $sudo_cmd apt-get install -y -qq --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi
