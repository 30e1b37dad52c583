#!/usr/bin/env python3
"""summary.png: accuracy against cost over every benchmark, one small chart per benchmark.

Usage: summary.py summary.csv summary.png target
summary.csv is compare.csv's columns over several benchmarks (`duet summary`). Each chart: the
largest scored error (%) against wall time (s), log-log, one line per method through its completed
runs (each point a spacing), the target as a dashed line, failed runs as red crosses on the top
edge (counted in the chart's title). Every chart has the same error axis and each method the same
colour in every chart, so the grid reads across benchmarks.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from compare import log_axis, number, percent, plain, wall_time_limits  # noqa: E402

COLOURS = {"sph": "tab:blue", "espfem": "tab:orange", "ispfem": "tab:green"}


def main():
    source, target_png, target = sys.argv[1], sys.argv[2], float(sys.argv[3])
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    errors = [number(r["max_rel_error"]) for r in rows
              if r["status"] == "completed" and number(r["max_rel_error"])]
    low = min(errors + [target]) / 2
    high = max(errors + [target]) * 2
    top = high / 1.4  # where failed runs are drawn
    columns = min(3, max(len(scenes), 1))
    lines = max(math.ceil(len(scenes) / columns), 1)
    fig, axes = plt.subplots(lines, columns, figsize=(3.6 * columns, 3.0 * lines + 0.5),
                             squeeze=False)
    methods = []
    for ax, scene in zip(axes.flat, scenes):
        runs = [r for r in rows if r["scene"] == scene]
        failed = [r for r in runs if r["status"] != "completed"]
        scored = False
        for method in dict.fromkeys(r["method"] for r in runs):
            colour = COLOURS.get(method)
            ok = [r for r in runs if r["method"] == method and r["status"] == "completed"
                  and number(r["max_rel_error"]) and number(r["wall_seconds"])]
            ok.sort(key=lambda r: number(r["wall_seconds"]))
            if ok:
                scored = True
                (line,) = ax.plot([number(r["wall_seconds"]) for r in ok],
                                  [number(r["max_rel_error"]) for r in ok], "o-", ms=4,
                                  color=colour, label=method)
                if method not in methods:
                    methods.append(method)
                    COLOURS.setdefault(method, line.get_color())
            lost = [r for r in failed if r["method"] == method and number(r["wall_seconds"])]
            if lost:
                ax.plot([number(r["wall_seconds"]) for r in lost], [top] * len(lost), "x",
                        color=colour or "red", ms=7, mew=2)
        ax.axhline(target, color="grey", ls="--", lw=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(low, high)
        wall_time_limits(ax, runs)
        log_axis(ax.xaxis, plain)
        log_axis(ax.yaxis, percent)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.35)
        title = scene + (f" ({len(failed)} failed: x)" if failed else "")
        ax.set_title(title, fontsize=9)
        if not scored:
            ax.text(0.5, 0.5, "no completed scored run", transform=ax.transAxes, ha="center",
                    va="center", fontsize=8)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    for ax in list(axes.flat)[:len(scenes)]:
        ax.set_xlabel("wall time (s)", fontsize=8)
    for ax in axes[:, 0]:
        ax.set_ylabel("largest scored error", fontsize=8)
    handles = [plt.Line2D([], [], color=COLOURS[m], marker="o", label=m) for m in methods]
    handles.append(plt.Line2D([], [], color="grey", ls="--", label=f"target {100 * target:g} %"))
    fig.legend(handles=handles, loc="upper center", ncol=len(handles), fontsize=8,
               frameon=False)
    fig.tight_layout(rect=(0, 0, 1, 1 - 0.45 / (3.0 * lines + 0.5)))
    fig.savefig(target_png, dpi=110)


if __name__ == "__main__":
    main()
