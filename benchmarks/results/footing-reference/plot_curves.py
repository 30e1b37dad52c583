"""Curve measures of several runs against reference CSVs on one chart (benchmarks/RESULTS.md,
"Footing").

Usage (Debian's python3, with h5py and matplotlib):
  /usr/bin/python3 plot_curves.py OUT.png "TITLE" MEASURE REF.csv[,REF.csv...] LABEL=RUN_DIR [...]
MEASURE is a measure with at = "curve" in every run (its abscissa read from the run's scene); the
reference CSVs are drawn dashed and labelled by their file name, the first one's scored window of
the first run shaded. Only runs whose metrics.json says `completed` are drawn; any other stops the
script with its status.
"""
import json
import os
import sys
import tomllib

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_csv(path):
    rows = [line for line in open(path) if line.strip() and not line.startswith("#")][1:]
    return np.array([[float(v) for v in row.split(",")] for row in rows])


def main():
    out, title, measure, refs = sys.argv[1:5]
    runs = [a.split("=", 1) for a in sys.argv[5:]]
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    window = None
    for ref in refs.split(","):
        pts = read_csv(ref)
        ax.plot(pts[:, 0], pts[:, 1], "k--" if window is None else "k:", lw=1.1,
                label=os.path.relpath(ref, start=os.getcwd()))
        window = window or True
    window = None
    for label, folder in runs:
        metrics = json.load(open(os.path.join(folder, "metrics.json")))
        if metrics.get("status") != "completed":
            raise SystemExit(f"{folder}: {metrics.get('status')}: not drawn")
        with h5py.File(os.path.join(folder, "run.h5"), "r") as h5:
            scene = tomllib.loads(h5["meta/scene_toml"][()].decode())
            m = scene["measure"][measure]
            x = h5["series"][m["abscissa"]][()]
            y = h5["series"][measure][()]
        score = metrics["accuracy"][measure]
        ax.plot(x, y, lw=1.3, label=f"{label}: worst {100 * score['signed_error']:+.1f} % at "
                f"{score['worst_at']:.3g}, mean {100 * score['mean_error']:.1f} %, "
                f"{metrics['wall_seconds']:.0f} s")
        window = window or m["x_window"]
    if window:
        ax.axvspan(window[0], window[1], color="0.85", alpha=0.5, lw=0, label="scored window")
    ax.set_xlabel("w / B")
    ax.set_ylabel("q / c_u")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


main()
