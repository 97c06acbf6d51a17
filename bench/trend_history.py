#!/usr/bin/env python3
"""What `aoreplay trend` says on histories built from real runs (issue 26's acceptance figures).

Runs the same build as A (the default, gtao high: 3 slices) and as B (`--set slices=4`, one GTAO
slice more: a real slowdown), interleaved (A, B, A, B, ... then the remaining A runs), so drift of
the machine falls on both. B's report.json says slices=4; the copy that is recorded says 3, as a
commit that made the same settings one slice slower would (otherwise B would be a series of its
own). Then, for each of SHUFFLES seeds, with R runs a commit (--runs-per-commit, as R CI runners
recording the same commit):
  change:    B-RUNS of the A runs, shuffled, as commits c01, c02, ... (R each), then all B runs
             shuffled as the commits after; trend must name the first B commit and nothing else;
  no change: all A runs shuffled as commits n01, n02, ...; trend must find no change.
Each history is its own SQLite store. Prints one line per history and the counts. Runs already in
OUT_DIR/runs are kept (delete the folder for new ones).
  python3 bench/trend_history.py BUILD_DIR OUT_DIR [--a-runs 60] [--b-runs 45] [--runs-per-commit 5] [--shuffles 20]
"""
import argparse
import json
import os
import random
import subprocess
import sys


def run(aoreplay, capture, out, extra):
    subprocess.run([aoreplay, "run", capture, "--frames", "0:4", "--repeat", "10", "--warmup", "2", "--no-images",
                    "--out", out] + extra, check=True, stdout=subprocess.DEVNULL)


def as_three_slices(src, dst):
    report = json.load(open(src))
    assert report["settings"]["slices"] == 4, src
    report["settings"]["slices"] = 3
    json.dump(report, open(dst, "w"), indent=1)


def record_history(aoreplay, store, commits):
    for suffix in ("", "-wal", "-shm"):
        if os.path.exists(store + suffix):
            os.remove(store + suffix)
    for ordinal, (sha, reports) in enumerate(commits, start=1):
        subprocess.run([aoreplay, "record", *reports, "--db", store, "--commit", sha, "--ordinal", str(ordinal)],
                       check=True, stdout=subprocess.DEVNULL)
    result = subprocess.run([aoreplay, "trend", "--db", store, "--json", "-"], capture_output=True, text=True)
    if result.returncode not in (0, 1):
        sys.exit(f"trend failed: {result.stderr}")
    (series,) = json.loads(result.stdout)["series"]
    return result.returncode, series


def describe(changes):
    if not changes:
        return "no change"
    out = []
    for c in changes:
        where = c["first_commit"] if not c["range"] else f'{c["first_commit"]}..{c["last_commit"]}'
        total = next(p for p in c["passes"] if p["pass"] == "total")
        out.append(f'{c["direction"]} at {where} (total x{total["ratio"]:.3f} [x{total["interval"][0]:.3f}, '
                   f'x{total["interval"][1]:.3f}])')
    return "; ".join(out)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("build")
    parser.add_argument("out")
    parser.add_argument("--a-runs", type=int, default=60)
    parser.add_argument("--b-runs", type=int, default=45)
    parser.add_argument("--runs-per-commit", type=int, default=5)
    parser.add_argument("--shuffles", type=int, default=20)
    parser.add_argument("--runs-only", action="store_true", help="take the missing runs, judge nothing")
    args = parser.parse_args()
    aoreplay = os.path.join(args.build, "replay", "aoreplay")
    capture = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "captures", "boxes-orbit")
    runs = os.path.join(args.out, "runs")
    a = [os.path.join(runs, f"a{i:02d}", "report.json") for i in range(1, args.a_runs + 1)]
    b = [os.path.join(runs, f"b{i:02d}", "recorded.json") for i in range(1, args.b_runs + 1)]
    os.makedirs(runs, exist_ok=True)
    for i in range(1, max(args.a_runs, args.b_runs) + 1):  # interleaved: A, B, A, B, ...
        if i <= args.a_runs and not os.path.exists(a[i - 1]):
            run(aoreplay, capture, os.path.join(runs, f"a{i:02d}"), [])
        if i <= args.b_runs and not os.path.exists(b[i - 1]):
            run(aoreplay, capture, os.path.join(runs, f"b{i:02d}"), ["--set", "slices=4"])
            as_three_slices(os.path.join(runs, f"b{i:02d}", "report.json"), b[i - 1])
    if args.runs_only:
        return
    totals = lambda files: sorted(json.load(open(f))["gpu_ms_total_median"] for f in files)
    ta, tb = totals(a), totals(b)
    print(f"A: {len(a)} runs, total {ta[0]:.3f}..{ta[-1]:.3f} ms (median {ta[len(ta) // 2]:.3f}); "
          f"B (one slice more): {len(b)} runs, {tb[0]:.3f}..{tb[-1]:.3f} ms (median {tb[len(tb) // 2]:.3f})")
    stores = os.path.join(args.out, "stores")
    os.makedirs(stores, exist_ok=True)
    named, alarms = 0, 0
    per = args.runs_per_commit
    as_commits = lambda prefix, files: [(f"{prefix}{i // per + 1:02d}", files[i:i + per]) for i in range(0, len(files), per)]
    changed_at = f"c{len(b) // per + 1:02d}"
    for seed in range(1, args.shuffles + 1):
        rng = random.Random(seed)
        commits = as_commits("c", rng.sample(a, len(b)) + rng.sample(b, len(b)))
        rc, series = record_history(aoreplay, os.path.join(stores, f"change{seed:02d}.sqlite"), commits)
        ch = series["changes"]
        ok = (len(ch) == 1 and not ch[0]["range"] and ch[0]["first_commit"] == changed_at
              and ch[0]["direction"] == "slower" and rc == 1)
        named += ok
        print(f"change    seed {seed:2d}: exit {rc}, {describe(ch)}{'' if ok else '  <- MISS'}")
    for seed in range(1, args.shuffles + 1):
        rng = random.Random(1000 + seed)
        commits = as_commits("n", rng.sample(a, len(a)))
        rc, series = record_history(aoreplay, os.path.join(stores, f"flat{seed:02d}.sqlite"), commits)
        alarm = bool(series["changes"]) or rc != 0
        alarms += alarm
        print(f"no change seed {seed:2d}: exit {rc}, {describe(series['changes'])}{'  <- ALARM' if alarm else ''}")
    print(f"change named at {changed_at} and nothing else: {named} of {args.shuffles}; "
          f"no change, no alarm: {args.shuffles - alarms} of {args.shuffles}")


if __name__ == "__main__":
    main()
