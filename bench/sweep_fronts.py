#!/usr/bin/env python3
"""Issue 50's sweep summary: for each `aoreplay sweep --cost instructions` folder, every
configuration's RMSE and halo-band RMSE against its counted instructions, the Pareto front of each
(no other configuration has both fewer instructions and a lower error), a markdown table, and a
plot of both errors against cost with their fronts (OUT/NAME_fronts.svg).

Usage: sweep_fronts.py OUT SWEEP_FOLDER...
"""
import json
import pathlib
import sys

from plot_svg import Plot, pareto_front

COLOURS = {"gtao": "#d62728", "xegtao": "#1f77b4", "vbao": "#2ca02c"}


def front(rows, key):
    points = [(r["instructions_total"], r[key]) for r in rows]
    return {rows[i]["configuration"] for i in pareto_front(points)}


def svg(name, rows, path):
    plot = Plot(f"{name}: RMSE (circles) and halo-band RMSE (squares) against counted instructions",
                "million instructions (lavapipe, callgrind; frames summed)", "error against the ray-traced reference",
                [r["instructions_total"] / 1e6 for r in rows], [v for r in rows for v in (r["rmse"], r["halo_band_rmse"])],
                x_digits=0, y_digits=3)
    for key, dash in (("rmse", ""), ("halo_band_rmse", "5 3")):
        plot.line([(r["instructions_total"] / 1e6, r[key]) for r in rows if r["configuration"] in front(rows, key)], "#555", dash)
    for r in rows:
        c = COLOURS.get(r["settings"]["technique"], "#777")
        x = plot.X(r["instructions_total"] / 1e6)
        plot.out.append(f'<circle cx="{x:.1f}" cy="{plot.Y(r["rmse"]):.1f}" r="3.5" fill="{c}"><title>{r["configuration"]}: RMSE {r["rmse"]:.4f}</title></circle>')
        plot.out.append(f'<rect x="{x-3:.1f}" y="{plot.Y(r["halo_band_rmse"])-3:.1f}" width="6" height="6" fill="none" stroke="{c}"><title>{r["configuration"]}: halo {r["halo_band_rmse"]:.4f}</title></rect>')
    for i, (t, c) in enumerate(COLOURS.items()):
        plot.out.append(f'<circle cx="{plot.w-plot.m-90}" cy="{plot.m+14*i}" r="4" fill="{c}"/><text x="{plot.w-plot.m-80}" y="{plot.m+14*i+4}">{t}</text>')
    plot.write(path, "lines: Pareto fronts (solid RMSE, dashed halo band)")


def main():
    out = pathlib.Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for folder in map(pathlib.Path, sys.argv[2:]):
        doc = json.loads((folder / "sweep.json").read_text())
        rows = doc["rows"]
        fr, fh = front(rows, "rmse"), front(rows, "halo_band_rmse")
        print(f"\n### {doc['capture']} (frames {doc['frames'][0]}:{doc['frames'][1]})\n")
        print("| configuration | M instructions | RMSE | halo-band RMSE | halo bias | front |")
        print("|---|---|---|---|---|---|")
        for r in rows:
            tags = ",".join(t for t, s in (("rmse", fr), ("halo", fh)) if r["configuration"] in s)
            print(f'| {r["configuration"]} | {r["instructions_total"]/1e6:.1f} | {r["rmse"]:.4f} | {r["halo_band_rmse"]:.4f} | '
                  f'{r["error"]["halo_band"]["bias"]:+.4f} | {tags} |')
        svg(doc["capture"], rows, out / f'{doc["capture"]}_fronts.svg')


if __name__ == "__main__":
    main()
