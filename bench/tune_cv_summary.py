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

from plot_svg import Plot, pareto_front


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


def svg(rows, path):
    points = [(r["ms_before"], r["before"], r["technique"] + " defaults") for r in rows] + \
             [(r["ms_after"], r["after"], r["technique"] + (" tuned" if r["recommended"] == "tuned" else " fit (refused)"))
              for r in rows]
    plot = Plot("held-out RMSE (cross-validated) against GPU ms per frame, defaults and tuned",
                "GPU ms per frame (lavapipe, median compute total, mean over the library)", "held-out RMSE (mean over folds)",
                [p[0] for p in points], [p[1] for p in points])
    plot.line([points[i][:2] for i in pareto_front([p[:2] for p in points])], "#c33", "4 3")
    for x, y, label in points:
        colour = "#36c" if "defaults" in label else "#c60"
        filled = "refused" not in label
        plot.out.append(f'<circle cx="{plot.X(x):.1f}" cy="{plot.Y(y):.1f}" r="4" fill="{colour if filled else "white"}" stroke="{colour}"/>')
        plot.out.append(f'<text x="{plot.X(x)+6:.1f}" y="{plot.Y(y)-5:.1f}">{label}</text>')
    plot.write(path, "dashed: Pareto front; blue: defaults, orange: the cross-validated fit (hollow: refused)")


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
