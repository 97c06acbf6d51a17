#!/usr/bin/env bash
# docs/cli.md is what the binary's --help says (cli_doc.py --check), and the check fails on a copy
# with one help line changed, naming the file and showing the line.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
aoreplay=$1 doc=$2 work=$3
python3 "$here/cli_doc.py" "$aoreplay" --check "$doc"
mkdir -p "$work"
sed 's/replay a capture through a technique/REPLAY A CAPTURE THROUGH A TECHNIQUE/' "$doc" > "$work/cli.md"
! cmp -s "$doc" "$work/cli.md"
set +e
out=$(python3 "$here/cli_doc.py" "$aoreplay" --check "$work/cli.md")
rc=$?
set -e
echo "$out"
[ "$rc" -eq 1 ]
grep -q "^-.*REPLAY A CAPTURE THROUGH A TECHNIQUE" <<< "$out"
grep -q "cli.md differs from the binary's --help" <<< "$out"
