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

COLOURS = {"gtao": "#d62728", "xegtao": "#1f77b4", "vbao": "#2ca02c"}


def front(rows, key):
    return {r["configuration"] for r in rows
            if not any(q["instructions_total"] <= r["instructions_total"] and q[key] < r[key] for q in rows if q is not r)}


def svg(name, rows, path):
    w, h, m = 760, 460, 64
    xs = [r["instructions_total"] / 1e6 for r in rows]
    ys = [v for r in rows for v in (r["rmse"], r["halo_band_rmse"])]
    x0, x1, y0, y1 = 0, max(xs) * 1.05, min(ys) * 0.95, max(ys) * 1.03
    X = lambda x: m + (x - x0) / (x1 - x0) * (w - 2 * m)
    Y = lambda y: h - m - (y - y0) / (y1 - y0) * (h - 2 * m)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w/2}" y="20" text-anchor="middle" font-size="13">{name}: RMSE (circles) and halo-band RMSE (squares) against counted instructions</text>',
           f'<line x1="{m}" y1="{h-m}" x2="{w-m}" y2="{h-m}" stroke="black"/><line x1="{m}" y1="{m}" x2="{m}" y2="{h-m}" stroke="black"/>',
           f'<text x="{w/2}" y="{h-22}" text-anchor="middle">million instructions (lavapipe, callgrind; frames summed)</text>',
           f'<text x="16" y="{h/2}" transform="rotate(-90 16 {h/2})" text-anchor="middle">error against the ray-traced reference</text>']
    for k in range(5):
        xv, yv = x0 + (x1 - x0) * k / 4, y0 + (y1 - y0) * k / 4
        out.append(f'<text x="{X(xv):.0f}" y="{h-m+15}" text-anchor="middle">{xv:.0f}</text>')
        out.append(f'<text x="{m-5}" y="{Y(yv)+4:.0f}" text-anchor="end">{yv:.3f}</text>')
    for key, dash in (("rmse", ""), ("halo_band_rmse", "5 3")):
        f = sorted((r["instructions_total"] / 1e6, r[key]) for r in rows if r["configuration"] in front(rows, key))
        out.append(f'<polyline fill="none" stroke="#555" stroke-dasharray="{dash}" points="' +
                   " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in f) + '"/>')
    for r in rows:
        t = r["settings"]["technique"]
        c = COLOURS.get(t, "#777")
        x = X(r["instructions_total"] / 1e6)
        out.append(f'<circle cx="{x:.1f}" cy="{Y(r["rmse"]):.1f}" r="3.5" fill="{c}"><title>{r["configuration"]}: RMSE {r["rmse"]:.4f}</title></circle>')
        out.append(f'<rect x="{x-3:.1f}" y="{Y(r["halo_band_rmse"])-3:.1f}" width="6" height="6" fill="none" stroke="{c}"><title>{r["configuration"]}: halo {r["halo_band_rmse"]:.4f}</title></rect>')
    for i, (t, c) in enumerate(COLOURS.items()):
        out.append(f'<circle cx="{w-m-90}" cy="{m+14*i}" r="4" fill="{c}"/><text x="{w-m-80}" y="{m+14*i+4}">{t}</text>')
    out.append(f'<text x="{w-m}" y="{m+50}" text-anchor="end">lines: Pareto fronts (solid RMSE, dashed halo band)</text></svg>')
    path.write_text("\n".join(out) + "\n")


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
