#!/usr/bin/env bash
# Two OpenGL 3.3 core programs from Debian packages that know nothing of aoreplay, captured with
# `aoreplay renderdoc-capture` under xvfb-run, then imported and replayed with no display at all
# (the import starts its own private Xvfb):
# - Godot 3 (godot3) running tests/renderdoc/godot3_boxes, a scene written for this test: the
#   camera in the uniform block SceneData, the scene in an FBO with a D24 renderbuffer, then a
#   tone-mapping pass into the window (passed over by the default event);
# - Qt's hellogles3 (qtbase5-examples), 1024 instanced logos: the camera in default-block
#   uniforms ($Globals), the window's own D32 depth (a back buffer with a 64-bit resource id).
# Usage: gl_programs_import_test.sh AOREPLAY SOURCE_DIR WORK_DIR
set -euo pipefail
aoreplay=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*"; cat "$work/log" 2>/dev/null; exit 1; }
expect() { grep -q -- "$1" "$work/log" || fail "no '$1'"; }

# import_and_replay NAME VIEW PROJECTION PATTERN...: headless import of NAME.rdc, its summary
# checked for each PATTERN (grep), then replayed under the validation layer.
import_and_replay() {
  local name=$1 view=$2 projection=$3
  shift 3
  env -u DISPLAY -u EGL_PLATFORM "$aoreplay" import renderdoc "$work/$name.rdc" --out "$work/$name" \
    --view "$view" --projection "$projection" >"$work/log" 2>&1 || fail "importing $name"
  cat "$work/log"
  expect "(RenderDoc 1.24[^,]*, OpenGL, replayed on a private X display (Xvfb :[0-9]*))"
  expect " 0 disagree"
  for pattern in "$@"; do expect "$pattern"; done
  env -u DISPLAY "$aoreplay" run "$work/$name" --validate --no-images --out "$work/$name-run" >"$work/log" 2>&1 \
    || fail "replaying $name"
  expect "validation: 0 messages"
}

# Godot writes .import/ into its project folder: it runs on a copy.
cp -r "$source/godot3_boxes" "$work/godot3_boxes"
HOME="$work" xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/godot.rdc" --after-frames 30 --timeout 120 \
  -- godot3 --path "$work/godot3_boxes" >"$work/log" 2>&1 || fail "capturing Godot 3"
import_and_replay godot SceneData.camera_inverse_matrix SceneData.projection_matrix \
  "last draw that tests and writes depth (1 later draw with depth test or writes off passed over)" \
  "depth: Renderbuffer [0-9]* (id [0-9]*), D24 320x180" "adjusted: clip z in \[-1, 1\]"

hellogles3=/usr/lib/x86_64-linux-gnu/qt5/examples/opengl/hellogles3/hellogles3
xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/hellogles3.rdc" --after-frames 30 --timeout 120 \
  -- "$hellogles3" -geometry 320x180 >"$work/log" 2>&1 || fail "capturing hellogles3"
import_and_replay hellogles3 '$Globals.camMatrix' '$Globals.projMatrix' \
  "depth: Backbuffer Depth (id [0-9]\{11,\}), D32 320x180" "view: \$Globals.camMatrix (vertex shader, column-major, default-block uniforms)"
echo "PASSED"
