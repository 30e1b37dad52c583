"""p/c_u against a/a0 of espfem cavity runs beside the closed form of the scene's 20 m ring.

Usage: /usr/bin/python3 plot_curves.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...]
Each RUN_DIR is a `duet run benchmarks/scenes/cavity.toml --method espfem ...` output folder;
its status is read from metrics.json and a run that did not complete is drawn dashed.
"""
import json
import math
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def ring(a, i_r=33.4, a0=1.0, b0=20.0):
    # Yu 2000 ch. 3, incompressible Tresca ring with a traction-free outer radius (cavity.toml)
    c2 = i_r * (a * a - a0 * a0)
    b2 = b0 * b0 + a * a - a0 * a0
    return 1.0 - c2 / b2 + math.log(c2 / (a * a))


def main():
    out, runs = sys.argv[1], sys.argv[2:]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    xs = [1.0 + 0.005 * k for k in range(1, 201)]
    ax.plot(xs, [ring(x) for x in xs], "k-", lw=2, label="closed form, 20 m ring")
    for spec in runs:
        label, folder = spec.split("=", 1)
        with open(folder + "/metrics.json") as f:
            status = json.load(f)["status"]
        with h5py.File(folder + "/run.h5", "r") as f:
            a = f["series/expansion"][:]
            p = f["series/pressure_curve"][:]
        style = "-" if status == "completed" else "--"
        ax.plot(a, p, style, lw=0.8, label=f"{label} ({status})")
    for x in (1.2, 1.5, 2.0):
        ax.axvline(x, color="0.8", lw=0.5)
    ax.set_xlabel("a / a0")
    ax.set_ylabel("p / c_u")
    ax.set_xlim(1.0, 2.0)
    ax.set_ylim(0.0, 6.0)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("cavity.toml through espfem: wall pressure (samples, 100 per second)")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
