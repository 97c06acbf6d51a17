#!/usr/bin/env bash
# vkcube (Debian's vulkan-tools) knows nothing of RenderDoc or aoreplay: capture one of its frames
# with `aoreplay renderdoc-capture` under Xvfb, import it, and check that the import finds its
# depth, refuses its one combined model-view-projection named as two matrices, and imports it as
# --view-projection.
# Usage: vkcube_import_test.sh AOREPLAY WORK_DIR
set -euo pipefail
aoreplay=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*"; cat "$work/log" 2>/dev/null; exit 1; }

xvfb-run -a "$aoreplay" renderdoc-capture --out "$work/vkcube.rdc" -- vkcube --c 100000 --width 320 --height 180 \
  || fail "capturing vkcube"

# The only uniform block holds MVP: naming it for both matrices is refused after the depth is found.
set +e
"$aoreplay" import renderdoc "$work/vkcube.rdc" --out "$work/imported" --view ubuf.MVP --projection ubuf.MVP \
  >"$work/log" 2>&1
status=$?
set -e
cat "$work/log"
[ "$status" -eq 2 ] || fail "exit status $status, expected 2"
grep -q "event [0-9]* vkCmdDraw(): last draw with a depth target" "$work/log" || fail "no event line"
grep -q "depth: 2D Depth Attachment [0-9]* (id [0-9]*), D16 320x180; viewport 180x180 at (70, 0), cropped to it" \
  "$work/log" || fail "no depth line"
grep -q -- "--view and --projection both name ubuf.MVP: a combined matrix is given as --view-projection ubuf.MVP" \
  "$work/log" || fail "combined matrix not named"
grep -q "ubuf \[vertex shader: MVP (float4x4)" "$work/log" || fail "the existing block not listed"
[ ! -e "$work/imported" ] || fail "--out was written"

# Asking for separate matrices names what the block lacks.
set +e
"$aoreplay" import renderdoc "$work/vkcube.rdc" --out "$work/imported" --view ubuf.view --projection ubuf.projection \
  >"$work/log" 2>&1
status=$?
set -e
cat "$work/log"
[ "$status" -eq 2 ] || fail "exit status $status, expected 2"
grep -q "uniform block ubuf (vertex shader) has no member view; its members: MVP (float4x4)" "$work/log" \
  || fail "missing member not named"
[ ! -e "$work/imported" ] || fail "--out was written"
# Given as what it is, the combined matrix (vkcube's P.V.M, its model a rotation) is factored, the
# frame passes the self-check against vkcube's own vertices, and it replays.
"$aoreplay" import renderdoc "$work/vkcube.rdc" --out "$work/imported" --view-projection ubuf.MVP >"$work/log" 2>&1 \
  || fail "--view-projection ubuf.MVP did not import"
cat "$work/log"
grep -q "view-projection: ubuf.MVP (vertex shader, column-major): factored into a perspective projection and a rigid view" \
  "$work/log" || fail "no factoring line"
grep -q "self-check: .* 0 disagree" "$work/log" || fail "self-check figures missing"
"$aoreplay" run "$work/imported" --no-images --out "$work/run" >"$work/log" 2>&1 || fail "the imported capture does not replay"
echo "vkcube: depth found, a combined matrix named twice refused, --view-projection imported and replayed"
