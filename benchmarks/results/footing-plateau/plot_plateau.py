"""footing.toml through ispfem: q/c_u against w/B, one panel per group of runs
(benchmarks/RESULTS.md, "The footing's plateau from w/B 0.05").

Usage (Debian's python3, with h5py and matplotlib):
  /usr/bin/python3 plot_plateau.py [--method=NAME] OUT.png "TITLE" LABEL=RUN_DIR [...] [-- "TITLE" LABEL=RUN_DIR ...]
(--method names the method in the figure's title: ispfem unless given; runs of any method draw.)
Each RUN_DIR is a `duet run` output folder of footing.toml or a variant of it (B = 2 m, c_u =
10 kPa: w/B = -settlement / 2, q/c_u = load_settlement / 1e4). Only runs whose metrics.json says
`completed` are drawn; any other stops the script.
"""
import json
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRANDTL = 2.0 + 3.141592653589793


def groups(args):
    out, current = [], None
    for a in args:
        if a == "--":
            current = None
        elif current is None:
            current = (a, [])
            out.append(current)
        else:
            current[1].append(a)
    return out


def main(out, args, method="ispfem"):
    panels = groups(args)
    fig, axes = plt.subplots(1, len(panels), figsize=(6.2 * len(panels), 4.6), squeeze=False)
    for ax, (title, runs) in zip(axes[0], panels):
        for item in runs:
            label, folder = item.rsplit("=", 1)  # labels may hold "=", folders not
            with open(folder + "/metrics.json") as f:
                status = json.load(f)["status"]
            if status != "completed":
                sys.exit("%s: status %s, not drawn" % (folder, status))
            with h5py.File(folder + "/run.h5", "r") as h5:
                w = [-x / 2.0 for x in h5["series/settlement"][:]]
                q = [x * 1e-4 for x in h5["series/load_settlement"][:]]
            ax.plot(w, q, lw=1.2, label=label)
        ax.axhline(PRANDTL, color="k", lw=0.8)
        ax.axhspan(0.98 * PRANDTL, 1.02 * PRANDTL, color="0.8", zorder=0.5)
        ax.axvspan(0.05, 0.1, color="0.93", zorder=0)
        ax.set_xlim(0.0, 0.1)
        ax.set_ylim(0.0, 6.0)
        ax.set_xlabel("w / B")
        ax.set_ylabel("q / c_u")
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=8, loc="lower right")
    fig.suptitle("footing through " + method + ": Prandtl 5.14 +- 2 % (band), scored window w/B 0.05-0.1", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    argv = sys.argv[1:]
    method = "ispfem"
    if argv and argv[0].startswith("--method="):
        method = argv.pop(0).split("=", 1)[1]
    main(argv[0], argv[1:], method)
