#!/usr/bin/env python3
"""Snapshots of several runs of one scene side by side, on one colour scale.

Usage: snapshots.py OUT.png FIELD RUN_DIR [RUN_DIR ...]
One row per run (its method and spacing), each its first, middle and last frames (the middle at
one time for every run: the median of the runs' mid-flow times, run.py's middle_frame), every
panel on the same axes' extent and the same colour scale: the 1st to 99th
percentile of FIELD over all the frames drawn, so that a colour means one value in every run
(`duet demo` and `duet compare` draw it; each run's own snapshots_<FIELD>.png has its own scale).
A run without frames is left out and said.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import run as single  # noqa: E402  (run.py beside this file)


def main():
    if len(sys.argv) < 4:
        raise SystemExit(__doc__)
    target, field, folders = sys.argv[1], sys.argv[2], sys.argv[3:]
    with_frames = []
    for folder in folders:
        r = single.Run(folder)
        if r.frames:
            with_frames.append(r)
        else:
            print(f"snapshots.py: {folder} has no frames; left out", file=sys.stderr)
    if not with_frames:
        raise SystemExit("snapshots.py: no run with frames")
    # One middle time for every row: the median of the runs' own mid-flow times
    middle = float(np.median([single.frame_time(r, single.middle_frame(r))
                              for r in with_frames]))
    runs = [(r, single.snapshot_frames(r, field, single.nearest_frame(r, middle)))
            for r in with_frames]
    spacing = max(float(r.h5["meta"].attrs["spacing"]) for r, _ in runs)
    every = [g for _, groups in runs for g in groups]
    limits = single.extent(every, spacing)
    colours = single.colour_range(every, field)
    xmin, xmax, ymin, ymax = limits
    aspect = min(max((ymax - ymin) / max(xmax - xmin, 1e-12), 0.25), 2.0)
    columns = max(len(groups) for _, groups in runs)
    panel = 3.6
    fig, axes = plt.subplots(len(runs), columns,
                             figsize=(panel * columns + 1.4, (panel * aspect + 0.9) * len(runs)),
                             squeeze=False, layout="constrained")
    fig.canvas.draw()  # lay out first: the marker size needs the axes' size
    art = None
    for row, (r, groups) in zip(axes, runs):
        own_spacing = float(r.h5["meta"].attrs["spacing"])
        for ax, g in zip(row, groups):
            art = single.draw_frame(fig, ax, g, field, own_spacing, limits, colours)
        for ax in row[len(groups):]:
            ax.set_visible(False)
        row[0].set_ylabel(f"{r.metrics.get('method', '?')}, dp = {own_spacing:g} m\n"
                          f"({r.status})\ny (m)", fontsize=8)
    fig.colorbar(art, ax=list(np.ravel(axes)), shrink=0.8,
                 label=single.field_label(field) + ", one scale for every run")
    scene = runs[0][0].metrics.get("scene", "?")
    fig.suptitle(f"{scene}: {field} through {len(runs)} runs", fontsize=10)
    fig.savefig(target, dpi=110)
    print(target)


if __name__ == "__main__":
    main()
