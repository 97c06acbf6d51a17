#!/usr/bin/env bash
# The three HTML reports in a real browser (headless Debian chromium): made from the shipped
# capture, checked by check_pages.py (no console error, no failed load, key elements present),
# screenshotted; then two pages broken on purpose must fail the same check.
#   browser_test.sh AOREPLAY WORKDIR [SCREENSHOT_DIR]
# With SCREENSHOT_DIR (docs/outputs.md shows those in docs/screenshots/) the screenshots are copied there.
set -euo pipefail
aoreplay=$1 work=$2 publish=${3:-}
here=$(cd "$(dirname "$0")" && pwd)
capture=$here/../../captures/boxes-orbit
rm -rf "$work" && mkdir -p "$work"

"$aoreplay" run "$capture" --frames 0:8 --out "$work/run" >"$work/run.log"
"$aoreplay" sweep "$capture" --frames 0:2 --presets low,medium,high --repeat 1 --out "$work/sweep" >"$work/sweep.log" 2>&1
for side in a b; do
  "$aoreplay" run "$capture" --frames 0:3 --repeat 5 --no-images --out "$work/$side" >>"$work/compare-runs.log"
done
status=0
"$aoreplay" compare "$work/a/report.json" "$work/b/report.json" --html "$work/compare.html" >"$work/compare.log" || status=$?
[ "$status" -le 1 ] || { cat "$work/compare.log"; exit 1; }

python3 "$here/check_pages.py" --screenshots "$work/screenshots" \
  run="$work/run/report.html" sweep="$work/sweep/sweep.html" compare="$work/compare.html"

# The check must catch a page that throws and a page that lost a key element.
sed 's|</body>|<script>undefinedFunctionOnPurpose();</script></body>|' "$work/run/report.html" >"$work/throws.html"
sed 's|<section id="memory">|<section id="no-memory">|' "$work/run/report.html" >"$work/incomplete.html"
for broken in throws incomplete; do
  if python3 "$here/check_pages.py" --screenshots "$work/broken" run="$work/$broken.html" >"$work/$broken.log"; then
    echo "browser_test: the check passed $broken.html, broken on purpose:"; cat "$work/$broken.log"; exit 1
  fi
  echo "browser_test: $broken.html fails as it should: $(grep -m1 -v 'FAILED' "$work/$broken.log")"
done

if [ -n "$publish" ]; then
  mkdir -p "$publish"
  for kind in run sweep compare; do cp "$work/screenshots/$kind.png" "$publish/report-$kind.png"; done
  echo "browser_test: screenshots copied to $publish"
fi
echo "browser_test: ok"
