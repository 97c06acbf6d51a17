#!/usr/bin/env python3
"""Side-by-side table: ao_bench medians (Google Benchmark JSON) next to the naive baseline's output.

usage: summarize.py ao_bench.json baseline-before.txt [baseline-after.txt]
The baseline column shows before / after when both are given; the ratio uses their mean.
"""
import json
import re
import statistics
import sys


def bench_medians(path):
    """name -> median of the repetitions' manual (GPU timestamp) time in ms."""
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
    samples = {}
    for b in json.load(open(path))["benchmarks"]:
        if b.get("run_type") == "iteration":
            name = re.sub(r"/iterations:.*", "", b["run_name"])
            samples.setdefault(name, []).append(b["real_time"] * scale[b["time_unit"]])
    return {name: statistics.median(v) for name, v in samples.items()}


def baseline_medians(path):
    """(size, 'SxT') -> gpu_med_ms from the baseline's table."""
    rows = {}
    for line in open(path):
        m = re.match(r"^(\d+x\d+)\s+(\d+)\s+(\d+)\s+([\d.]+)\s", line)
        if m:
            rows[(m.group(1), f"{m.group(2)}x{m.group(3)}")] = float(m.group(4))
    return rows


def main():
    bench = bench_medians(sys.argv[1])
    baselines = [baseline_medians(path) for path in sys.argv[2:]]
    sizes = sorted({size for size, _ in baselines[0]}, key=lambda s: int(s.split("x")[0]))
    print("| size | preset | naive baseline 1 pass | pipeline (bent=1) | pipeline (bent=0) | linearize | gtao | spatial (both dispatches) | temporal | pipeline / baseline |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for size in sizes:
        for preset, st, variant in (("low", "1x2", ""), ("medium", "2x2", ""), ("high", "3x3", ""),
                                    ("high, half_res=1", "3x3", "/half_res:1"), ("ultra", "9x3", "")):
            name = preset.split(",")[0]
            key = f"gtao/{name}{variant}/{size}"
            pipe = bench.get(f"pipeline/{key}")
            bases = [b.get((size, st)) for b in baselines]
            if pipe is None or None in bases:
                continue
            base = sum(bases) / len(bases)
            cells = [bench.get(f"{p}/{key}") for p in ("linearize_depth", "gtao", "spatial", "temporal")]
            columns = bench.get(f"spatial_columns/{key}")  # the blur's first dispatch, since issue 6
            if columns is not None and cells[2] is not None:
                cells[2] += columns
            bent0 = None if variant else bench.get(f"pipeline/gtao/{name}/bent:0/{size}")
            fmt = lambda v: "-" if v is None else f"{v:.3f}"
            print(f"| {size} | {preset} | {' / '.join(f'{b:.3f}' for b in bases)} | {pipe:.3f} | {fmt(bent0)} | "
                  + " | ".join(fmt(c) for c in cells) + f" | {pipe / base:.2f} |")
    print("\nmedian GPU ms (timestamp queries) per repetition; same device, same invocation of run_bench.sh")


if __name__ == "__main__":
    main()
