#!/usr/bin/env bash
# check_links.py on the repository passes, and on a small repository of its own with a missing
# file and a missing heading it fails naming both (and accepts the links that do resolve).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
work=$1
python3 "$here/check_links.py"
rm -rf "$work" && mkdir -p "$work/docs" && cd "$work" && git init -q
printf '# Title\n\n## Some `code` here\n\nSee [b](docs/b.md#second-part), [self](#some-code-here), [web](https://example.org),\n[gone](docs/missing.md) and [bad anchor](docs/b.md#nowhere).\n\n```\n[not a link](nowhere.md)\n```\n' > a.md
printf '# B\n\n## Second part\n' > docs/b.md
git add a.md docs/b.md
set +e
out=$(python3 "$here/check_links.py" "$work")
rc=$?
set -e
echo "$out"
[ "$rc" -eq 1 ]
grep -qx 'a.md:6: docs/missing.md: no such file' <<< "$out"
grep -qx 'a.md:6: docs/b.md#nowhere: no heading with anchor #nowhere' <<< "$out"
[ "$(grep -c ': no ' <<< "$out")" -eq 2 ]
