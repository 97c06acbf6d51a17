#!/usr/bin/env python3
"""Every relative link in the project's Markdown resolves (issue 55: docs as reference).

Reads every tracked *.md file (git ls-files), takes each inline link or image `[text](target)`
that is not a URL (http, https, mailto), and checks that the target exists relative to the file;
for a target `FILE.md#anchor` or `#anchor`, that the Markdown file has a heading with that
GitHub anchor (lower case, punctuation but - and _ dropped, spaces to -). Code spans and fenced
blocks are skipped. Usage: check_links.py [ROOT] (default: the repository holding this script).
Exit 1 with one line per broken link (file:line: target: why); 0 and a count otherwise.
"""
import pathlib
import re
import subprocess
import sys

LINK = re.compile(r'!?\[[^\]]*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')
HEADING = re.compile(r'^#{1,6}\s+(.*?)\s*#*\s*$')


def anchor_of(heading):
    text = re.sub(r'`([^`]*)`', r'\1', heading).strip().lower()
    text = re.sub(r'[^\w\- ]', '', text)
    return text.replace(' ', '-')


def unfenced_lines(path):
    """(line number, text) outside fenced blocks."""
    fenced = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def prose_lines(path):
    """The same with code spans removed: links inside them are examples, not links."""
    for number, line in unfenced_lines(path):
        yield number, re.sub(r'`[^`]*`', '', line)


def anchors(path, cache={}):
    if path not in cache:
        found, seen = set(), {}
        for _, line in unfenced_lines(path):
            m = HEADING.match(line)
            if m:
                a = anchor_of(m.group(1))
                n = seen.get(a, 0)
                seen[a] = n + 1
                found.add(a if n == 0 else f"{a}-{n}")
        cache[path] = found
    return cache[path]


def problems(root, md):
    for number, line in prose_lines(md):
        for target in LINK.findall(line):
            if re.match(r'^[a-z]+:', target):
                continue
            file_part, _, anchor = target.partition('#')
            resolved = (md.parent / file_part).resolve() if file_part else md
            if not resolved.exists():
                yield number, target, "no such file"
            elif anchor and resolved.suffix == ".md" and anchor not in anchors(resolved):
                yield number, target, f"no heading with anchor #{anchor}"


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[2])
    files = subprocess.run(["git", "ls-files", "*.md"], cwd=root, capture_output=True, text=True, check=True).stdout.split()
    broken, links = [], 0
    for name in files:
        md = root / name
        for number, target, why in problems(root, md):
            broken.append(f"{name}:{number}: {target}: {why}")
        links += sum(len(LINK.findall(line)) for _, line in prose_lines(md))
    for line in broken:
        print(line)
    if broken:
        print(f"{len(broken)} broken link(s)")
        return 1
    print(f"doc links: {links} links in {len(files)} Markdown files resolve")
    return 0


if __name__ == "__main__":
    sys.exit(main())
