#!/usr/bin/env python3
"""Summarises bench/tune_cv_library.sh: per technique every fold's held-out RMSE before and after,
the verdict, and held-out RMSE (the folds' mean: the cross-validated estimate) against GPU time at
the defaults and tuned; writes OUT/tuned-against-tuned.md and OUT/tuned-against-tuned.svg (the
Pareto front over all points: no other point has both lower RMSE and lower time).

Usage: tune_cv_summary.py OUT TECHNIQUE...
"""
import json
import pathlib
import sys


def load(out, technique):
    folder = out / technique
    tune = json.loads((folder / "tune.json").read_text())
    times = json.loads((folder / "tune_times.json").read_text())
    cv = tune["cross_validation"]
    folds = cv["folds"]
    recommended = cv["recommended"]
    before = sum(f["before"] for f in folds) / len(folds)
    after = sum(f["after"] for f in folds) / len(folds)  # the fit's cross-validated estimate, refused or not
    training = times["results"]["training"]
    return {"technique": technique, "folds": folds, "recommended": recommended, "refused_by": cv.get("refused_by"),
            "margin": cv["margin"], "before": before, "after": after, "ms_before": training["before"]["ms"],
            "ms_after": training["after"]["ms"], "keys": [k["key"] for k in tune["keys"]],
            "worst": max(folds, key=change), "settings": tune["settings"]}


def change(f):
    if f["before"] > 0:
        return f["after"] / f["before"] - 1
    return float("inf") if f["after"] > 0 else 0.0


def pareto(points):
    return [p for p in points if not any(q[0] <= p[0] and q[1] <= p[1] and q != p for q in points)]


def svg(rows, path):
    points = [(r["ms_before"], r["before"], r["technique"] + " defaults") for r in rows] + \
             [(r["ms_after"], r["after"], r["technique"] + (" tuned" if r["recommended"] == "tuned" else " fit (refused)"))
              for r in rows]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    x0, x1, y0, y1 = 0, max(xs) * 1.1, min(ys) * 0.9, max(ys) * 1.05
    w, h, m = 720, 440, 60
    X = lambda x: m + (x - x0) / (x1 - x0) * (w - 2 * m)
    Y = lambda y: h - m - (y - y0) / (y1 - y0) * (h - 2 * m)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w/2}" y="20" text-anchor="middle" font-size="13">held-out RMSE (cross-validated) against GPU ms per frame, defaults and tuned</text>',
           f'<line x1="{m}" y1="{h-m}" x2="{w-m}" y2="{h-m}" stroke="black"/><line x1="{m}" y1="{m}" x2="{m}" y2="{h-m}" stroke="black"/>',
           f'<text x="{w/2}" y="{h-20}" text-anchor="middle">GPU ms per frame (lavapipe, median compute total, mean over the library)</text>',
           f'<text x="15" y="{h/2}" transform="rotate(-90 15 {h/2})" text-anchor="middle">held-out RMSE (mean over folds)</text>']
    for k in range(5):
        xv, yv = x0 + (x1 - x0) * k / 4, y0 + (y1 - y0) * k / 4
        out.append(f'<text x="{X(xv):.0f}" y="{h-m+15}" text-anchor="middle">{xv:.2f}</text>')
        out.append(f'<text x="{m-5}" y="{Y(yv)+4:.0f}" text-anchor="end">{yv:.4f}</text>')
    front = sorted(pareto([(p[0], p[1]) for p in points]))
    out.append('<polyline fill="none" stroke="#c33" stroke-dasharray="4 3" points="' +
               " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in front) + '"/>')
    for x, y, label in points:
        colour = "#36c" if "defaults" in label else "#c60"
        filled = "refused" not in label
        out.append(f'<circle cx="{X(x):.1f}" cy="{Y(y):.1f}" r="4" fill="{colour if filled else "white"}" stroke="{colour}"/>')
        out.append(f'<text x="{X(x)+6:.1f}" y="{Y(y)-5:.1f}">{label}</text>')
    out.append(f'<text x="{w-m}" y="{m-8}" text-anchor="end" fill="#c33">dashed: Pareto front; blue: defaults, orange: the cross-validated fit (hollow: refused)</text></svg>')
    path.write_text("\n".join(out) + "\n")


def main():
    out = pathlib.Path(sys.argv[1])
    rows = [load(out, t) for t in sys.argv[2:] if (out / t / "tune.json").exists()]
    lines = ["| technique | tuned keys | held-out RMSE, defaults | the fit, cross-validated | recommended | worst fold | margin it would pass | ms defaults | ms fit |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        w = r["worst"]
        lines.append(f'| {r["technique"]} | {", ".join(r["keys"])} | {r["before"]:.4f} | {r["after"]:.4f} ({100*(r["after"]/r["before"]-1):+.1f} %) |'
                     f' {r["recommended"]} | {w["held_out"]} {100*change(w):+.1f} % | {100*max(change(w), 0):.1f} % |'
                     f' {r["ms_before"]:.3f} | {r["ms_after"]:.3f} |')
    lines += ["", "Per fold (held-out RMSE before -> after the fit on the other captures):", ""]
    for r in rows:
        lines.append(f'- {r["technique"]}: ' + "; ".join(
            f'{f["held_out"]} {f["before"]:.4f} -> {f["after"]:.4f} ({100*change(f):+.1f} %)' for f in r["folds"]))
    (out / "tuned-against-tuned.md").write_text("\n".join(lines) + "\n")
    if rows:
        svg(rows, out / "tuned-against-tuned.svg")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
