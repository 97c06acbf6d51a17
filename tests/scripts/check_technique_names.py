#!/usr/bin/env python3
"""Nothing outside a technique names it or one of its keys (replay/techniques/README.md).

Asks the binary for the registered techniques and their keys (`aoreplay techniques --json`), then
reads every C++ file of replay/ outside the folders that own techniques and keys (techniques/,
technique_api/ for the run's radius, shared_passes/ for the shared denoisers' keys) and names the
file, line and word of:
- a string literal that is a technique's name or key, or an assignment "KEY=..." of one;
- a Settings accessor or technique lookup given such a literal (`.has("temporal")`,
  `findTechnique("reference")`), whatever the word.
A few keys are also ordinary words of the output schema (report.json's `metrics.temporal`,
`error.bias`, `gpu_ms.samples`): SCHEMA_WORDS lists them with where they occur; as JSON field
names they pass, inside an accessor they are still refused.

Usage: check_technique_names.py AOREPLAY [ROOT]   (ROOT: the repository, default ..)
Exit 1 with one line per finding; 0 and a count otherwise.
"""
import json
import pathlib
import re
import subprocess
import sys

OWNERS = {"techniques", "technique_api", "shared_passes"}
# Keys that are also field names of the outputs or inputs, and where.
SCHEMA_WORDS = {
    "reference": "capture.json frames[].reference; report.json error.reference (the reference's kind)",
    "bias": "report.json metrics.error.bias and halo_band.bias",
    "samples": "report.json passes[].gpu_ms.samples; RenderDoc's depth samples; the store's sample count",
    "radius": "report.json halo_band.radius; the generator's --radius",
    "temporal": "report.json metrics.temporal (temporal stability)",
    "thin": "the generator's scene of thin occluders",
}
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
ACCESSOR = re.compile(
    r'(?:(?:\.|->)(?:has|f|i|b|set|text|parameter|assign)\(|\.value\((?="[^"]*"\s*\))|findTechnique\()\s*"([^"]*)"')


def registered(binary):
    listing = json.loads(subprocess.run([binary, "techniques", "--json"], check=True, capture_output=True, text=True).stdout)
    names = {t["name"] for t in listing["techniques"]}
    keys = {p["key"] for t in listing["techniques"] for p in t["parameters"]}
    return names, keys


def code_only(line):
    """The line without its // comment (a // inside a string literal is kept)."""
    out, in_string, i = [], False, 0
    while i < len(line):
        c = line[i]
        if c == '\\' and in_string:
            out.append(line[i:i + 2])
            i += 2
            continue
        if c == '"':
            in_string = not in_string
        elif not in_string and line.startswith("//", i):
            break
        out.append(c)
        i += 1
    return "".join(out)


def word_of(literal):
    return literal.split("=", 1)[0] if "=" in literal else literal


def findings(path, names, keys):
    words = names | keys
    for number, raw in enumerate(path.read_text().splitlines(), 1):
        line = code_only(raw)
        for m in ACCESSOR.finditer(line):
            if word_of(m.group(1)) in words:
                yield number, m.group(1), "passed to a settings accessor or technique lookup"
        for m in LITERAL.finditer(line):
            literal = m.group(1)
            word = word_of(literal)
            if word not in words or (literal == word and word in SCHEMA_WORDS):
                continue
            kind = "technique" if word in names else "key"
            yield number, literal, f"names a {kind} outside its technique"


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    root = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else pathlib.Path(__file__).resolve().parents[2])
    names, keys = registered(sys.argv[1])
    found = 0
    files = 0
    for path in sorted((root / "replay").rglob("*")):
        if path.suffix not in (".cpp", ".h") or path.relative_to(root / "replay").parts[0] in OWNERS:
            continue
        files += 1
        for number, literal, why in sorted(set(findings(path, names, keys))):
            print(f"{path.relative_to(root)}:{number}: \"{literal}\" {why}")
            found += 1
    if found:
        print(f"{found} finding(s); a technique's names and keys belong in replay/techniques/NAME/ "
              "(declare what the tool needs from it in technique_api/technique.h)")
        sys.exit(1)
    print(f"no technique or key named outside its technique: {files} files, {len(names)} techniques, {len(keys)} keys")


if __name__ == "__main__":
    main()
