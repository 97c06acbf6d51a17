#!/usr/bin/env python3
"""Is a refactor behaviour-neutral? Runs two aoreplay binaries (before and after) on the same inputs
and compares what they write:

- every command's --help (byte-identical, or differing only by the --renamed OLD=NEW words);
- `techniques --json` (byte-identical);
- every shipped capture (captures/*/capture.json) under every built-in technique at its default
  preset, every debug view read back: each image byte-identical, report.json identical apart from
  its timing keys (TIMING below) and `tool_version`;
- `sweep` over every technique on one capture: sweep.csv identical apart from its timing columns
  (*_ms) and `pareto` (chosen by time);
- `capture` of every synthetic scene (one small frame, with a reference): every file byte-identical.

Usage: compare_builds.py OLD_AOREPLAY NEW_AOREPLAY WORK_DIR [--captures DIR] [--renamed OLD=NEW ...]
Prints one line per comparison that differs and a table of counts; exit 1 when anything differs.
Takes about 4 minutes a binary on a 2-core machine (the reference technique is most of it).
"""
import argparse
import csv
import filecmp
import json
import os
import re
import shutil
import subprocess
import sys

# report.json keys that hold measured time (they differ between two runs of one binary).
# Every key named *_ms or *_ms_* (gpu_ms_median, host_ms, setup_ms, bvh_build_ms, ...) and these.
TIMING = re.compile(r"(^|\.)([a-z_]*_ms(_[a-z_]+)?|host_overhead|replay_fps|tool_version)(\.|\[|$)")
# Files a run writes whose content is measured time.
TIMED_FILES = {"report.html", "trace.json"}
SCENES = ["plane", "pit", "sphere", "boxes", "bunny", "thin"]


def run(binary, arguments, log):
    with open(log, "w") as out:
        return subprocess.run([binary] + arguments, stdout=out, stderr=subprocess.STDOUT).returncode


def output_of(binary, arguments):
    return subprocess.run([binary] + arguments, capture_output=True, text=True).stdout


def flatten(value, prefix=""):
    if isinstance(value, dict):
        for key, item in value.items():
            yield from flatten(item, prefix + "." + key)
    elif isinstance(value, list):
        for index, item in enumerate(value):
            yield from flatten(item, "%s[%d]" % (prefix, index))
    else:
        yield prefix, value


def report_differences(old_file, new_file):
    old = {k: v for k, v in flatten(json.load(open(old_file))) if not TIMING.search(k)}
    new = {k: v for k, v in flatten(json.load(open(new_file))) if not TIMING.search(k)}
    return sorted(k for k in old.keys() | new.keys() if old.get(k) != new.get(k))


def sweep_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    # Times, and the Pareto front, which is chosen by time.
    return [{k: v for k, v in row.items() if not k.endswith("_ms") and k != "pareto"} for row in rows]


class Comparison:
    def __init__(self):
        self.counts = {}
        self.differences = []

    def record(self, kind, what, same, detail=""):
        compared, differing = self.counts.get(kind, (0, 0))
        self.counts[kind] = (compared + 1, differing + (0 if same else 1))
        if not same:
            self.differences.append("%s: %s differs%s" % (kind, what, ": " + detail if detail else ""))
            print(self.differences[-1], flush=True)

    def folders(self, kind, old_dir, new_dir):
        """Every file of two output folders: report.json by its untimed keys, the rest byte for byte."""
        names = set()
        for root in (old_dir, new_dir):
            for folder, _, files in os.walk(root):
                names |= {os.path.relpath(os.path.join(folder, f), root) for f in files}
        for name in sorted(names):
            if os.path.basename(name) in TIMED_FILES:
                continue
            old, new = os.path.join(old_dir, name), os.path.join(new_dir, name)
            if not (os.path.exists(old) and os.path.exists(new)):
                self.record(kind, name, False, "written by one build only")
            elif name.endswith("report.json"):
                keys = report_differences(old, new)
                self.record(kind, name, not keys, ", ".join(keys[:5]))
            else:
                self.record(kind, name, filecmp.cmp(old, new, shallow=False))


def renamed(text, renames):
    for old, new in renames:
        text = text.replace(old, new)
    return text


def compare_help(binaries, c, renames):
    top = output_of(binaries["new"], ["--help"])
    commands = [""] + re.findall(r"^  ([a-z][a-z-]+)\s", top.split("Subcommands:")[-1], re.M)
    for command in commands:
        arguments = ([command] if command else []) + ["--help"]
        old, new = (output_of(binaries[side], arguments).replace(binaries[side], "aoreplay") for side in ("old", "new"))
        c.record("help", "aoreplay %s--help" % (command + " " if command else ""), renamed(old, renames) == new)


def run_with_debug_views(binary, capture, technique, out):
    """A run reading back every debug view the technique writes at its default preset (a view
    some settings do not write is refused by name: dropped, and the run made again)."""
    views = [v["name"] for v in technique["debug_views"]]
    while True:
        arguments = ["run", capture, "--technique", technique["name"], "--out", out, "--warmup", "0"]
        for view in views:
            arguments += ["--debug", view]
        status = run(binary, arguments, out + ".log")
        missing = re.search(r"writes no debug view '([a-z_0-9]+)'", open(out + ".log").read())
        if status == 0 or not missing or missing.group(1) not in views:
            return status
        views.remove(missing.group(1))


def compare_runs(binaries, work, captures, techniques, c):
    for capture in captures:
        for technique in techniques:
            outs = {}
            for side, binary in binaries.items():
                outs[side] = os.path.join(work, side, "runs", os.path.basename(capture), technique["name"])
                os.makedirs(os.path.dirname(outs[side]), exist_ok=True)
                status = run_with_debug_views(binary, capture, technique, outs[side])
                c.record("run exit", "%s %s (%s)" % (os.path.basename(capture), technique["name"], side), status == 0)
            c.folders("run " + technique["name"], outs["old"], outs["new"])


def compare_sweep(binaries, work, capture, techniques, c):
    outs = {}
    grid = "technique=" + ",".join(t["name"] for t in techniques if t["name"] != "reference")
    for side, binary in binaries.items():
        outs[side] = os.path.join(work, side, "sweep")
        status = run(binary, ["sweep", capture, "--grid", grid, "--frames", "0:2",
                              "--repeat", "1", "--warmup", "0", "--out", outs[side]], outs[side] + ".log")
        c.record("sweep exit", side, status == 0)
    old, new = (os.path.join(outs[s], "sweep.csv") for s in ("old", "new"))
    if os.path.exists(old) and os.path.exists(new):
        c.record("sweep.csv", "sweep.csv (untimed columns)", sweep_rows(old) == sweep_rows(new))
    else:
        c.record("sweep.csv", "sweep.csv", False, "not written")


def compare_captures(binaries, work, c):
    for scene in SCENES:
        outs = {}
        for side, binary in binaries.items():
            outs[side] = os.path.join(work, side, "capture", scene)
            status = run(binary, ["capture", scene, "--out", outs[side], "--size", "64x36", "--frames", "2",
                                  "--reference-spp", "4", "--depth2"], outs[side] + ".log")
            c.record("capture exit", "%s (%s)" % (scene, side), status == 0)
        c.folders("capture", outs["old"], outs["new"])


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("work")
    p.add_argument("--captures", default=os.path.join(os.path.dirname(__file__), "..", "..", "captures"))
    p.add_argument("--renamed", action="append", default=[], help="OLD=NEW: a word the help texts may differ by")
    args = p.parse_args()
    binaries = {"old": os.path.abspath(args.old), "new": os.path.abspath(args.new)}
    renames = [tuple(r.split("=", 1)) for r in args.renamed]
    shutil.rmtree(args.work, ignore_errors=True)
    for side in binaries:
        os.makedirs(os.path.join(args.work, side, "runs"))
        os.makedirs(os.path.join(args.work, side, "capture"))
    c = Comparison()
    compare_help(binaries, c, renames)
    listings = [output_of(binaries[side], ["techniques", "--json"]) for side in ("old", "new")]
    c.record("techniques --json", "techniques --json", listings[0] == listings[1])
    techniques = json.loads(listings[1])["techniques"]
    captures = sorted(os.path.dirname(f) for f in
                      (os.path.join(args.captures, d, "capture.json") for d in os.listdir(args.captures))
                      if os.path.exists(f))
    compare_runs(binaries, args.work, captures, techniques, c)
    compare_sweep(binaries, args.work, captures[0], techniques, c)
    compare_captures(binaries, args.work, c)
    print("\n| compared | files or outputs | differing |\n|---|---|---|")
    for kind, (compared, differing) in sorted(c.counts.items()):
        print("| %s | %d | %d |" % (kind, compared, differing))
    print("\n%s: %d captures x %d techniques; timing keys ignored: %s"
          % ("SAME" if not c.differences else "DIFFERENT", len(captures), len(techniques), TIMING.pattern))
    return 1 if c.differences else 0


if __name__ == "__main__":
    sys.exit(main())
