#!/usr/bin/env bash
# check_technique_names.py on the tree (no finding), then on a copy of replay/ with the faults it
# exists for put back on purpose: each must be named with its file and line, and the check fail.
set -euo pipefail
aoreplay=$1 work=$2
script=$(dirname "$0")/check_technique_names.py
root=$(cd "$(dirname "$0")/../.." && pwd)
python3 "$script" "$aoreplay" "$root"

rm -rf "$work" && mkdir -p "$work"
cp -r "$root/replay" "$work/replay"
cat >> "$work/replay/cli/run_command.cpp" <<'CPP'
float weightOf(const aor::Settings& settings) { return settings.has("temporal") ? settings.f("temporal") : 0.0f; }
const aor::Technique& theReference() { return aor::findTechnique("reference"); }
std::string fallback = "xegtao";  // a comment naming "cacao" is not code
CPP
if python3 "$script" "$aoreplay" "$work" > "$work/out.txt"; then
  echo "FAIL: the check passed a tree that names techniques and keys outside them"; cat "$work/out.txt"; exit 1
fi
cat "$work/out.txt"
n=$(wc -l < "$root/replay/cli/run_command.cpp")
for expected in "run_command.cpp:$((n + 1)): \"temporal\" passed to a settings accessor" \
                "run_command.cpp:$((n + 2)): \"reference\" passed to a settings accessor" \
                "run_command.cpp:$((n + 3)): \"xegtao\" names a technique outside its technique"; do
  grep -qF "$expected" "$work/out.txt" || { echo "FAIL: not reported: $expected"; exit 1; }
done
if grep -q '"cacao"' "$work/out.txt"; then echo "FAIL: a comment was taken for code"; exit 1; fi
echo "PASS: the tree is clean and each planted name is reported"
