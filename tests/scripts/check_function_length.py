#!/usr/bin/env python3
"""No function of replay/ longer than LIMIT lines (CONTRIBUTING: functions short).

Universal Ctags (Debian's universal-ctags) finds every C++ function and lambda with its first and
last line; a lambda counts inside the function that holds it, and on its own. Prints each function
over the limit with its file, line and length, then the distribution; exit 1 when any is over.

Usage: check_function_length.py [ROOT] [--limit N]   (ROOT: the repository, default ..)
"""
import argparse
import pathlib
import statistics
import subprocess
import sys


def functions(root):
    files = sorted(str(p) for p in (root / "replay").rglob("*") if p.suffix in (".cpp", ".h"))
    out = subprocess.run(["ctags", "--languages=C++", "--c++-kinds=f", "--fields=+ne", "-o", "-"] + files,
                         check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        parts = line.split("\t")
        fields = dict(p.split(":", 1) for p in parts[3:] if ":" in p)
        if "line" in fields and "end" in fields:
            yield parts[0], pathlib.Path(parts[1]).relative_to(root), int(fields["line"]), int(fields["end"])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("root", nargs="?", default=str(pathlib.Path(__file__).resolve().parents[2]))
    parser.add_argument("--limit", type=int, default=80)
    args = parser.parse_args()
    root = pathlib.Path(args.root).resolve()
    found = list(functions(root))
    lengths = [end - start + 1 for _, _, start, end in found]
    over = [(end - start + 1, path, start, name) for name, path, start, end in found if end - start + 1 > args.limit]
    for length, path, start, name in sorted(over, reverse=True):
        print(f"{path}:{start}: {name} is {length} lines (limit {args.limit})")
    print(f"{len(found)} functions in replay/: median {statistics.median(lengths):g} lines, "
          f"longest {max(lengths)}, {len(over)} over {args.limit}")
    sys.exit(1 if over else 0)


if __name__ == "__main__":
    main()
