"""footing-deep through ispfem: q/s_u against w/B for runs with and without the increment
stabilisation (benchmarks/RESULTS.md, "An increment stabilisation for ispfem").

Usage (Debian's python3, with h5py and matplotlib):
  /usr/bin/python3 plot_curves.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...]
Each RUN_DIR is a `duet run` output folder (run.h5 series `settlement`, `load_settlement`;
metrics.json for the status). A failed run is drawn dashed, its label saying where it stopped.
"""
import json
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out, runs):
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    for item in runs:
        label, folder = item.split("=", 1)
        with open(folder + "/metrics.json") as f:
            metrics = json.load(f)
        with h5py.File(folder + "/run.h5", "r") as h5:
            w = [-x for x in h5["series/settlement"][:]]  # B = 1 m
            q = list(h5["series/load_settlement"][:])
        failed = metrics["status"] != "completed"
        if failed:
            label += " (failed at w/B %.2f)" % w[-1]
        ax.plot(w, q, "--" if failed else "-", lw=1.2, label=label)
    ax.axhline(5.1416, color="k", lw=0.8, ls=":", label="Prandtl 2 + pi")
    ax.set_xlabel("w / B")
    ax.set_ylabel("q / s_u")
    ax.set_xlim(0.0, 1.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
