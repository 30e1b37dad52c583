"""Final deposits of collapse-bui through two or more runs, drawn over each other.

Usage: /usr/bin/python3 plot_deposits.py OUT.png LABEL=RUN_DIR [LABEL=RUN_DIR ...]
Each RUN_DIR is a `duet run` folder (its run.h5); the last frame is drawn, with the run's
status, end time and run-out read from its metrics.json (a failed run is labelled so).
"""
import json
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out, runs):
    fig, ax = plt.subplots(figsize=(9, 3.2))
    ax.plot([0.0, 0.2, 0.2], [0.1, 0.1, 0.0], "k--", lw=0.8, label="column at t = 0")
    for (label, folder), colour in zip(runs, ["tab:blue", "tab:orange", "tab:green", "tab:red"]):
        metrics = json.load(open(f"{folder}/metrics.json"))
        with h5py.File(f"{folder}/run.h5") as f:
            last = sorted(f["frames"].keys())[-1]
            p = f["frames"][last]["position"][:]
        runout = metrics["measures"].get("runout", float("nan"))
        status = metrics["status"]
        text = f"{label}: {status} at t = {metrics['end_time']:.2f} s, run-out {runout:.3f} m"
        if status != "completed":
            text += f" ({metrics['failure']['reason']})"
        ax.scatter(p[:, 0], p[:, 1], s=0.6, color=colour, label=text)
        ax.axvline(runout, color=colour, lw=0.8)
    ax.axvline(0.36, color="k", lw=0.8, ls=":", label="Lube et al. run-out law, 0.36 m")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal")
    ax.set_xlim(0.0, 0.55)
    ax.set_ylim(0.0, 0.11)
    ax.legend(loc="upper right", fontsize=7, markerscale=8)
    fig.tight_layout()
    fig.savefig(out, dpi=150)


if __name__ == "__main__":
    main(sys.argv[1], [tuple(a.split("=", 1)) for a in sys.argv[2:]])
