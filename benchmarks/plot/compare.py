#!/usr/bin/env python3
"""compare.png: scored error against wall time, log-log, one line per method.

Usage: compare.py compare.csv compare.png [title]
Each point is one (method, spacing) run, labelled by its spacing; failed runs are drawn as a
red cross at their wall time on the top edge, labelled with the spacing, so they are not dropped.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "error against cost"
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    methods = []
    for row in rows:
        if row["method"] not in methods:
            methods.append(row["method"])
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    finite_errors = [number(r["max_rel_error"]) for r in rows if number(r["max_rel_error"])]
    top = max(finite_errors) * 2 if finite_errors else 1.0
    for method in methods:
        runs = [r for r in rows if r["method"] == method]
        ok = [r for r in runs if r["status"] == "completed" and number(r["max_rel_error"])]
        ok.sort(key=lambda r: number(r["wall_seconds"]))
        if ok:
            x = [number(r["wall_seconds"]) for r in ok]
            y = [number(r["max_rel_error"]) for r in ok]
            (line,) = ax.plot(x, y, "o-", label=method)
            for r, xi, yi in zip(ok, x, y):
                ax.annotate(f"dp={r['spacing']}", (xi, yi), textcoords="offset points",
                            xytext=(4, 4), fontsize=7, color=line.get_color())
        for r in runs:
            if r["status"] != "completed":
                x = number(r["wall_seconds"]) or 1e-3
                ax.plot([x], [top], "x", color="red")
                ax.annotate(f"{method} dp={r['spacing']} failed", (x, top),
                            textcoords="offset points", xytext=(4, -10), fontsize=7, color="red")
    ax.set_xscale("log")
    ax.set_yscale("log")
    # At least a decade on each axis, so near-equal errors are not blown up into a steep line.
    if finite_errors:
        low, high = min(finite_errors), max(finite_errors)
        middle = (low * high) ** 0.5
        ax.set_ylim(min(low / 2, middle / 3.2), max(top * 1.5, middle * 3.2))
    times = [number(r["wall_seconds"]) for r in rows if number(r["wall_seconds"])]
    if times:
        middle = (min(times) * max(times)) ** 0.5
        ax.set_xlim(min(min(times) / 1.5, middle / 3.2), max(max(times) * 1.5, middle * 3.2))
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("largest relative error of the scored measures")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    if methods:
        ax.legend()
    fig.tight_layout()
    fig.savefig(target, dpi=120)


if __name__ == "__main__":
    main()
