#!/usr/bin/env python3
"""Checks every #include between folders of replay/ against the layer table of
docs/architecture.md: a folder may include its own headers and those of the folders it builds on,
transitively. Includes that resolve under shaders/ (GLSL headers shared with C++) are free.

Usage: check_layers.py [SOURCE_DIR]    (default: the repository holding this script)
Prints one line per violation (file:line: FOLDER includes OTHER/...: OTHER is not below FOLDER)
and exits 1 if there is any; a folder of replay/ missing from the table is a violation too.
"""
import os
import re
import sys

ROW = re.compile(r"^\| `([a-z_]+)` \|.*\| ([^|]+) \|\s*$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/([^"]+)"')


def read_layers(architecture):
    """{folder: set of folders it builds on directly}, in table order."""
    layers = {}
    for line in open(architecture, encoding="utf-8"):
        m = ROW.match(line)
        if m:
            layers[m.group(1)] = set(re.findall(r"`([a-z_]+)`", m.group(2)))
    return layers


def below(layers, folder, seen=None):
    """Every folder `folder` may include, itself excluded."""
    seen = set() if seen is None else seen
    for dependency in layers.get(folder, ()):
        if dependency not in seen:
            seen.add(dependency)
            below(layers, dependency, seen)
    return seen


def violations(source):
    replay = os.path.join(source, "replay")
    layers = read_layers(os.path.join(source, "docs", "architecture.md"))
    folders = sorted(d for d in os.listdir(replay) if os.path.isdir(os.path.join(replay, d)))
    for folder in folders:
        if folder not in layers:
            yield "replay/%s: a folder docs/architecture.md's layer table does not list" % folder
    for folder in folders:
        allowed = below(layers, folder) | {folder}
        for directory, _, files in os.walk(os.path.join(replay, folder)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp", ".inc")):
                    continue
                path = os.path.join(directory, name)
                for number, line in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
                    m = INCLUDE.match(line)
                    if not m or not os.path.exists(os.path.join(replay, m.group(1), m.group(2))):
                        continue  # a system header, or a shared GLSL header under shaders/
                    if m.group(1) not in allowed:
                        yield "%s:%d: %s includes %s/%s: %s is not below %s in docs/architecture.md" % (
                            os.path.relpath(path, source), number, folder, m.group(1), m.group(2), m.group(1), folder)


def main():
    source = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    found = list(violations(os.path.abspath(source)))
    for v in found:
        print(v)
    print("include layers: %s" % ("%d violation(s)" % len(found) if found else "every include follows docs/architecture.md"))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
