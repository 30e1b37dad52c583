#!/usr/bin/env python3
"""stability.png: stable / failed-with-reason per grid cell of the varied keys.

Usage: stability.py stability.csv stability.png [title]
One varied key: a row of cells; two or more: the first two keys span the grid (further keys
are listed in the cell text).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FIXED = ["status", "failure_reason", "failure_time", "steps", "wall_seconds", "max_rel_error"]


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "stability map"
    with open(source, newline="") as f:
        reader = csv.DictReader(f)
        keys = [k for k in reader.fieldnames if k not in FIXED]
        rows = list(reader)
    x_key = keys[0]
    y_key = keys[1] if len(keys) > 1 else None
    xs = list(dict.fromkeys(r[x_key] for r in rows))
    ys = list(dict.fromkeys(r[y_key] for r in rows)) if y_key else [""]
    fig, ax = plt.subplots(figsize=(1.6 * len(xs) + 2, 1.0 * len(ys) + 2))
    for r in rows:
        i = xs.index(r[x_key])
        j = ys.index(r[y_key]) if y_key else 0
        ok = r["status"] == "completed"
        ax.add_patch(plt.Rectangle((i, j), 1, 1, color="#8fd18f" if ok else "#f08c8c"))
        text = "stable" if ok else "failed\n" + r["failure_reason"][:40]
        extra = [f"{k}={r[k]}" for k in keys[2:]]
        ax.text(i + 0.5, j + 0.5, "\n".join([text] + extra), ha="center", va="center",
                fontsize=7, wrap=True)
    ax.set_xlim(0, len(xs))
    ax.set_ylim(0, len(ys))
    ax.set_xticks([i + 0.5 for i in range(len(xs))], xs)
    ax.set_xlabel(x_key)
    if y_key:
        ax.set_yticks([j + 0.5 for j in range(len(ys))], ys)
        ax.set_ylabel(y_key)
    else:
        ax.set_yticks([])
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(target, dpi=120)


if __name__ == "__main__":
    main()
