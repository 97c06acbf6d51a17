#!/usr/bin/env python3
"""Convergence of --technique rtao to a capture's Embree reference (replay/techniques/rtao/README.md).

Runs `aoreplay run CAPTURE --technique rtao --set distance_based=0 --set power=1` (the reference's
definition: cosine-weighted binary visibility within the radius) twice on a still capture, with
samples=1 and samples=16, so the accumulated frames give 1, 2, 4, ..., 256 samples per pixel, reads
each frame's RMSE against the reference from report.json, fits err^2 = a / n + c (sampling noise
falling as 1/n plus a floor c: the reference's own noise and any bias), and writes the table and an
SVG plot. Standard library only.

Usage: python3 replay/techniques/rtao/convergence.py [--exe build/replay/aoreplay]
       [--capture captures/boxes-static] [--out /tmp/rtao-convergence] [--svg FILE]
"""
import argparse
import json
import math
import os
import subprocess
import sys


def run(exe, capture, samples, frames, out):
    cmd = [exe, "run", capture, "--technique", "rtao", "--set", "distance_based=0", "--set", "power=1",
           "--set", f"samples={samples}", "--frames", f"0:{frames}", "--no-images", "--out", out]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    rows = []
    for frame in report["frames"]:
        rows.append((int(frame["technique"]["accumulated_spp"]), frame["metrics"]["error"]["rmse"],
                     frame["gpu_ms_median"].get("rtao", 0.0)))
    return rows, report


def fit(points):
    # Least squares of err^2 = a * (1/n) + c.
    xs = [1.0 / n for n, _ in points]
    ys = [e * e for _, e in points]
    m = len(xs)
    mx, my = sum(xs) / m, sum(ys) / m
    sxx = sum((x - mx) ** 2 for x in xs)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys))
    a = sxy / sxx
    return a, my - a * mx


def svg(points, a, c, path, title):
    w, h, left, right, top, bottom = 640, 420, 70, 20, 40, 60
    ns = [n for n, _ in points]
    es = [e for _, e in points]
    x0, x1 = math.log2(min(ns)), math.log2(max(ns))
    ylo = math.floor(math.log10(min(es + [math.sqrt(max(c, 1e-12))])) * 4) / 4
    yhi = math.ceil(math.log10(max(es)) * 4) / 4

    def px(n):
        return left + (math.log2(n) - x0) / (x1 - x0) * (w - left - right)

    def py(e):
        return top + (yhi - math.log10(e)) / (yhi - ylo) * (h - top - bottom)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w / 2}" y="22" text-anchor="middle" font-size="14">{title}</text>']
    for n in ns:
        out.append(f'<line x1="{px(n):.1f}" y1="{top}" x2="{px(n):.1f}" y2="{h - bottom}" stroke="#eee"/>')
        out.append(f'<text x="{px(n):.1f}" y="{h - bottom + 16}" text-anchor="middle">{n}</text>')
    k = ylo
    while k <= yhi + 1e-9:
        y = py(10 ** k)
        out.append(f'<line x1="{left}" y1="{y:.1f}" x2="{w - right}" y2="{y:.1f}" stroke="#eee"/>')
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end">{10 ** k:.3g}</text>')
        k += 0.25
    out.append(f'<text x="{w / 2}" y="{h - 18}" text-anchor="middle">samples per pixel (accumulated)</text>')
    out.append(f'<text x="16" y="{h / 2}" text-anchor="middle" transform="rotate(-90 16 {h / 2})">RMSE vs Embree reference</text>')
    e1 = points[0][1]
    ideal = " ".join(f"{px(n):.1f},{py(e1 / math.sqrt(n / points[0][0])):.1f}" for n in ns)
    out.append(f'<polyline points="{ideal}" fill="none" stroke="#999" stroke-dasharray="5,4"/>')
    model = " ".join(f"{px(n):.1f},{py(math.sqrt(a / n + c)):.1f}" for n in ns)
    out.append(f'<polyline points="{model}" fill="none" stroke="#e08020"/>')
    measured = " ".join(f"{px(n):.1f},{py(e):.1f}" for n, e in points)
    out.append(f'<polyline points="{measured}" fill="none" stroke="#2060c0" stroke-width="2"/>')
    for n, e in points:
        out.append(f'<circle cx="{px(n):.1f}" cy="{py(e):.1f}" r="3" fill="#2060c0"/>')
    lx, ly = w - right - 250, top + 14
    for i, (colour, dash, label) in enumerate([("#2060c0", "", "measured"),
                                               ("#999", ' stroke-dasharray="5,4"', "1/sqrt(n) from 1 spp"),
                                               ("#e08020", "", f"fit sqrt({a:.3g}/n + {c:.3g})")]):
        y = ly + 16 * i
        out.append(f'<line x1="{lx}" y1="{y}" x2="{lx + 24}" y2="{y}" stroke="{colour}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{lx + 30}" y="{y + 4}">{label}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", default="build/replay/aoreplay")
    p.add_argument("--capture", default="captures/boxes-static")
    p.add_argument("--out", default="/tmp/rtao-convergence")
    p.add_argument("--svg", default="replay/techniques/rtao/convergence-boxes-static.svg")
    args = p.parse_args()
    ones, _ = run(args.exe, args.capture, 1, 16, os.path.join(args.out, "samples1"))
    sixteens, report = run(args.exe, args.capture, 16, 16, os.path.join(args.out, "samples16"))
    wanted = [1, 2, 4, 8, 16, 32, 64, 128, 256]
    by_spp = {}
    for rows in (ones, sixteens):
        for n, e, ms in rows:
            if n in wanted and n not in by_spp:
                by_spp[n] = (e, ms)
    points = [(n, by_spp[n][0]) for n in wanted if n in by_spp]
    a, c = fit(points)
    with open(os.path.join(args.capture, "capture.json")) as f:
        reference_spp = json.load(f).get("scene", {}).get("reference_spp", "?")
    print(f"capture {args.capture}, reference_spp {reference_spp}")
    print("spp  rmse      rmse*sqrt(spp)  fit       measured/fit  rmse(1)/sqrt(spp)  measured/that")
    for n, e in points:
        model = math.sqrt(a / n + c)
        ideal = points[0][1] / math.sqrt(n)
        print(f"{n:4d} {e:.5f}  {e * math.sqrt(n):.5f}         {model:.5f}   {e / model:.3f}         {ideal:.5f}            {e / ideal:.3f}")
    print(f"fit: err^2 = {a:.5g} / n + {c:.5g}; floor sqrt(c) = {math.sqrt(max(c, 0)):.5f}")
    svg(points, a, c, args.svg, f"rtao on {os.path.basename(args.capture.rstrip('/'))}: distance_based=0 power=1")
    print(f"wrote {args.svg}")


if __name__ == "__main__":
    sys.exit(main())
