#!/usr/bin/env python3
"""docs/cli.md, the command-line reference, generated from the binary's own --help (issue 55: the
reference cannot drift from the program). `aoreplay --help` and `aoreplay COMMAND --help` for every
command it lists (and their own commands: `import renderdoc`), each in a section of its own; the binary's path in the usage lines is written as
`aoreplay`.

Usage: cli_doc.py AOREPLAY OUT.md         writes the reference
       cli_doc.py AOREPLAY --check FILE   exit 1 (with a diff) when FILE is not what the binary says
"""
import difflib
import re
import subprocess
import sys

HEADER = """# aoreplay command-line reference

Generated from `aoreplay --help` and each command's `--help` by `tests/scripts/cli_doc.py`; do not
edit: `python3 tests/scripts/cli_doc.py build/replay/aoreplay docs/cli.md` regenerates it, and the
ctest `cli_doc` fails when it differs from the binary. docs/guide.md says what the commands are for;
docs/outputs.md what they write.
"""


def help_of(binary, *command):
    out = subprocess.run([binary, *command, "--help"], capture_output=True, text=True, check=True).stdout
    return out.replace(binary, "aoreplay").rstrip() + "\n"


def commands(main_help):
    listed, inside = [], False
    for line in main_help.splitlines():
        if line.startswith("Subcommands:"):
            inside = True
        elif inside and (m := re.match(r"^  (\S+)\s", line)):
            listed.append(m.group(1))
    return listed


def sections(binary, path):
    """The help of `aoreplay PATH...` and, depth first, of every command it lists."""
    text = help_of(binary, *path)
    yield " ".join(["aoreplay", *path]), text
    for command in commands(text):
        yield from sections(binary, [*path, command])


def reference(binary):
    parts = [HEADER] + [f"## {title}\n\n```text\n{text}```\n" for title, text in sections(binary, [])]
    return "\n".join(parts)


def main():
    binary = sys.argv[1]
    if len(sys.argv) == 4 and sys.argv[2] == "--check":
        text = reference(binary)
        written = open(sys.argv[3], encoding="utf-8").read()
        if text == written:
            print(f"cli doc: {sys.argv[3]} is what the binary's --help says")
            return 0
        diff = difflib.unified_diff(written.splitlines(), text.splitlines(), sys.argv[3], "the binary's --help", lineterm="")
        print("\n".join(list(diff)[:60]))
        print(f"{sys.argv[3]} differs from the binary's --help: regenerate it with "
              f"python3 tests/scripts/cli_doc.py build/replay/aoreplay {sys.argv[3]}")
        return 1
    open(sys.argv[2], "w", encoding="utf-8").write(reference(binary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
