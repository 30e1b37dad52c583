#!/usr/bin/env python3
"""stability.png: one cell per combination of the varied settings.

Usage: stability.py stability.csv stability.png [title] [key=unit ...]
A completed cell is coloured by its largest scored error (a colour bar; "stable" in green when the
scene scores nothing); a failed or interrupted cell is red and names its reason: in the cell,
wrapped, when short, else as [k] with the reasons listed under the map. One varied key: a row of
cells; two or more: the first two keys span the grid, and each cell is split into side-by-side
sub-cells, one per combination of the further keys (named in each sub-cell).
Axis labels carry each key's unit when given.
"""
import csv
import math
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import LogNorm, Normalize  # noqa: E402
from matplotlib.ticker import FuncFormatter  # noqa: E402

FIXED = ["status", "failure_reason", "failure_time", "steps", "wall_seconds", "max_rel_error"]
SHORT = 48  # a reason up to this long is written in its cell


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "stability map"
    units = dict(a.split("=", 1) for a in sys.argv[4:] if "=" in a)
    with open(source, newline="") as f:
        reader = csv.DictReader(f)
        keys = [k for k in reader.fieldnames if k not in FIXED]
        rows = list(reader)
    x_key = keys[0]
    y_key = keys[1] if len(keys) > 1 else None
    xs = list(dict.fromkeys(r[x_key] for r in rows))
    ys = list(dict.fromkeys(r[y_key] for r in rows)) if y_key else [""]
    subs = list(dict.fromkeys(tuple(r[k] for k in keys[2:]) for r in rows))
    n_sub = len(subs)

    errors = [number(r["max_rel_error"]) for r in rows if r["status"] == "completed"]
    errors = [e for e in errors if e is not None]
    cmap = plt.get_cmap("viridis")
    norm = None
    if errors:
        low, high = min(errors), max(errors)
        norm = LogNorm(max(low, 1e-6), max(high, low * 1.01, 1e-6 * 1.01)) if low > 0 \
            else Normalize(low, max(high, low + 1e-12))

    reasons = []  # long reasons, listed under the map
    width = 1.9 * len(xs) * n_sub + 2.6
    fig, ax = plt.subplots(figsize=(width, 1.15 * len(ys) + 2.2))
    for r in rows:
        # the cell's left edge: its column, then its sub-column (further keys)
        i = xs.index(r[x_key]) + subs.index(tuple(r[k] for k in keys[2:])) / n_sub
        j = ys.index(r[y_key]) if y_key else 0
        extra = [f"{k.split('.')[-1]} = {r[k]}" for k in keys[2:]]
        if r["status"] == "completed":
            error = number(r["max_rel_error"])
            if norm is not None and error is not None:
                colour = cmap(norm(max(error, 1e-6)))
                text = f"{100 * error:.3g} %"
                ink = "white" if norm(max(error, 1e-6)) < 0.6 else "black"
            else:
                colour, text, ink = "#8fd18f", "stable", "black"
        else:
            colour, ink = "#f08c8c", "black"
            at = number(r["failure_time"])
            when = f" at {at:.3g} s" if at is not None else ""
            reason = r["failure_reason"] or r["status"]
            if len(reason) <= SHORT:
                text = f"{r['status']}{when}\n" + "\n".join(textwrap.wrap(reason, 22))
            else:
                reasons.append(f"{r['status']}{when}: {reason}")
                text = f"{r['status']}{when}\n[{len(reasons)}]"
        ax.add_patch(plt.Rectangle((i, j), 1 / n_sub, 1, facecolor=colour, edgecolor="white",
                                   lw=0.8 if n_sub > 1 else 2))
        ax.text(i + 0.5 / n_sub, j + 0.5, "\n".join([text] + extra), ha="center", va="center",
                fontsize=7, color=ink)
    for i in range(1, len(xs)):  # the main columns' borders over the sub-cells'
        ax.axvline(i, color="white", lw=3)
    ax.set_xlim(0, len(xs))
    ax.set_ylim(0, len(ys))

    def label(key):
        unit = units.get(key, "")
        return f"{key} ({unit})" if unit and unit != "-" else key

    ax.set_xticks([i + 0.5 for i in range(len(xs))], xs)
    ax.set_xlabel(label(x_key))
    if y_key:
        ax.set_yticks([j + 0.5 for j in range(len(ys))], ys)
        ax.set_ylabel(label(y_key))
    else:
        ax.set_yticks([])
    ax.set_title(title)
    if norm is not None:
        mappable = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
        bar = fig.colorbar(mappable, ax=ax, fraction=0.05, pad=0.02)
        bar.set_label("largest relative error (completed runs)")
        as_percent = FuncFormatter(lambda v, _p: f"{100 * v:.2g} %")
        bar.ax.yaxis.set_major_formatter(as_percent)
        bar.ax.yaxis.set_minor_formatter(as_percent)
    note = 0.0
    if reasons:
        lines = []
        for k, reason in enumerate(reasons, 1):
            lines.extend(textwrap.wrap(f"[{k}] {reason}", int(14 * width),
                                       subsequent_indent="     "))
        fig.text(0.02, 0.01, "\n".join(lines), fontsize=7, va="bottom", color="darkred")
        note = 0.15 * len(lines) + 0.15
        fig.set_figheight(fig.get_figheight() + note)
    fig.tight_layout(rect=(0, note / fig.get_figheight(), 1, 1))
    fig.savefig(target, dpi=120)


if __name__ == "__main__":
    main()
