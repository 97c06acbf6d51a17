#!/usr/bin/env bash
# `aoreplay renderdoc-capture` on programs from Debian packages that know nothing of it, under Xvfb:
#  - vkcube behind a wrapper script that execs it, and behind one that runs it as a child: the
#    capture follows the wrapper to the process that draws; --after-register and --after-trigger
#    run once each;
#  - glxgears (legacy OpenGL): refused with exit 2 and RenderDoc's own reason;
#  - a program that never draws: exit 2 when the time is up; an --out that is not a capture is kept;
#  - vkd3d-gears (a D3D12 demo running on vkd3d, its matrix a float4[7] of a cbuffer): captured,
#    imported with --view-projection cb0_0._child0[0], self-checked and replayed.
# Usage: renderdoc_capture_test.sh AOREPLAY WORK_DIR
set -euo pipefail
aoreplay=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*"; cat "$work/log" 2>/dev/null; exit 1; }
expect_refused() {  # expect_refused TEXT ARGS...: exit 2 and TEXT in the message
  local text=$1; shift
  set +e
  "$@" >"$work/log" 2>&1
  local status=$?
  set -e
  cat "$work/log"
  [ "$status" -eq 2 ] || fail "exit status $status, expected 2: $*"
  grep -qF -- "$text" "$work/log" || fail "no '$text' in the message"
}

printf '#!/bin/sh\nexec vkcube "$@"\n' >"$work/exec-wrapper.sh"
printf '#!/bin/sh\nvkcube "$@"\n' >"$work/child-wrapper.sh"
chmod +x "$work/exec-wrapper.sh" "$work/child-wrapper.sh"
for wrapper in exec-wrapper child-wrapper; do
  xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/$wrapper.rdc" --timeout 60 \
    --after-register "touch $work/$wrapper.registered" --after-trigger "touch $work/$wrapper.triggered" \
    -- "$work/$wrapper.sh" --c 100000 --width 320 --height 180 >"$work/log" 2>&1 || fail "capturing vkcube behind $wrapper"
  cat "$work/log"
  grep -q "captured frame [0-9]* of $work/$wrapper.sh (Vulkan, drawn by vkcube) into $work/$wrapper.rdc" "$work/log" \
    || fail "no capture line for $wrapper"
  [ -e "$work/$wrapper.registered" ] && [ -e "$work/$wrapper.triggered" ] || fail "the commands did not run ($wrapper)"
  "$aoreplay" import renderdoc "$work/$wrapper.rdc" --out "$work/$wrapper" --view-projection ubuf.MVP >"$work/log" 2>&1 \
    || fail "importing the $wrapper capture"
done
pgrep -x vkcube && fail "a captured vkcube is still running"

expect_refused "RenderDoc cannot capture /usr/bin/glxgears's OpenGL: Unsupported functions used:" \
  xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/glxgears.rdc" --timeout 30 -- glxgears
expect_refused "/bin/sleep did not use a graphics API RenderDoc can capture (is it presenting frames?) within the time limit" \
  "$aoreplay" renderdoc-capture --out "$work/sleep.rdc" --timeout 5 -- /bin/sleep 60
echo "not a capture" >"$work/notes.rdc"
expect_refused "field \"--out\": exists and is not a RenderDoc capture; not replacing it" \
  "$aoreplay" renderdoc-capture --out "$work/notes.rdc" -- vkcube
[ "$(cat "$work/notes.rdc")" = "not a capture" ] || fail "notes.rdc was changed"
[ ! -e "$work/glxgears.rdc" ] && [ ! -e "$work/sleep.rdc" ] || fail "a refused capture left a file"

xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/gears.rdc" -- vkd3d-gears >"$work/log" 2>&1 || fail "capturing vkd3d-gears"
"$aoreplay" import renderdoc "$work/gears.rdc" --out "$work/gears" --view-projection 'cb0_0._child0[0]' >"$work/log" 2>&1 \
  || fail "importing vkd3d-gears"
cat "$work/log"
grep -q "self-check: .* 0 disagree" "$work/log" || fail "vkd3d-gears: no self-check figures"
"$aoreplay" run "$work/gears" --no-images --out "$work/gears-run" >"$work/log" 2>&1 || fail "vkd3d-gears does not replay"
echo "renderdoc-capture: wrappers followed, legacy GL refused with RenderDoc's reason, vkd3d-gears imported and replayed"
