#!/usr/bin/env python3
"""srf.png: every strength-reduction trial's largest displacement against time.

Usage: srf.py srf.csv srf.png MEASURE [title]
One curve per trial (its run.h5 /series/MEASURE), blue when it settled, red when it kept moving
or its run failed (a failed run's curve ends where it stopped), labelled by its factor; the right
panel shows each trial's verdict against its factor, so the bracket reads at a glance.
"""
import csv
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    source, target, measure = sys.argv[1], sys.argv[2], sys.argv[3]
    title = sys.argv[4] if len(sys.argv) > 4 else "strength reduction"
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11.0, 4.4),
                                      gridspec_kw={"width_ratios": [2.2, 1]})
    for r in sorted(rows, key=lambda r: float(r["factor"])):
        path = os.path.join(r["dir"], "run.h5")
        stable = r["verdict"] == "stable"
        colour = "tab:blue" if stable else "tab:red"
        try:
            with h5py.File(path, "r") as h5:
                t = h5["series/time"][()]
                u = h5[f"series/{measure}"][()]
        except (OSError, KeyError):
            continue
        left.plot(t, u, color=colour, lw=1.2, alpha=0.85)
        if len(t):
            left.annotate(f"f = {float(r['factor']):.4g}", (t[-1], u[-1]), fontsize=7,
                          color=colour, xytext=(3, 0), textcoords="offset points")
    left.set_xlabel("time (s)")
    left.set_ylabel(f"{measure} (m)")
    left.grid(alpha=0.3)
    left.set_title("largest displacement per trial (blue settles, red does not)", fontsize=9)
    for r in rows:
        f = float(r["factor"])
        stable = r["verdict"] == "stable"
        right.plot([f], [1 if stable else 0], "o", color="tab:blue" if stable else "tab:red")
    stable = [float(r["factor"]) for r in rows if r["verdict"] == "stable"]
    failed = [float(r["factor"]) for r in rows if r["verdict"] != "stable"]
    if stable and failed and max(stable) < min(failed):
        right.axvspan(max(stable), min(failed), color="gold", alpha=0.4,
                      label=f"factor of safety in [{max(stable):.4g}, {min(failed):.4g}]")
        right.legend(fontsize=7, loc="center")
    right.set_yticks([0, 1], ["failed", "stable"])
    right.set_ylim(-0.5, 1.5)
    right.set_xlabel("strength reduction factor f")
    right.grid(alpha=0.3)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.savefig(target, dpi=110)


if __name__ == "__main__":
    main()
