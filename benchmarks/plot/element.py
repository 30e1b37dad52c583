#!/usr/bin/env python3
"""element.png: the stress path (q against p) and the stress-strain curve of one element test.

Usage: element.py element.csv element.png [title]
Stress-strain: q against axial strain, or shear stress against shear strain for simple shear
(detected from the csv: shear strain changes while the axial strain does not). Stresses are
tension positive in the csv; the axes show compression positive (-p, -axial strain) and kPa.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) if r[key] not in ("", "nan") else math.nan for r in rows]
            for key in rows[0]} if rows else {}


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "element test"
    data = read(source)
    fig, (path_ax, curve_ax) = plt.subplots(1, 2, figsize=(10, 4.2))
    if not data:
        fig.suptitle(title + " (no rows)")
        fig.savefig(target, dpi=120)
        return
    kpa = 1e-3
    path_ax.plot([-p * kpa for p in data["p"]], [q * kpa for q in data["q"]], "-", lw=1.5)
    path_ax.plot([-data["p"][0] * kpa], [data["q"][0] * kpa], "o", color="k", label="start")
    path_ax.set_xlabel("mean stress -p (kPa, compression positive)")
    path_ax.set_ylabel("deviatoric stress q (kPa)")
    path_ax.set_title("stress path")
    path_ax.legend(loc="best", fontsize=8)
    path_ax.grid(True, alpha=0.3)

    shear_span = max(data["shear_strain"]) - min(data["shear_strain"])
    axial_span = max(data["axial_strain"]) - min(data["axial_strain"])
    if shear_span > 0.0 and axial_span <= 1e-12:
        curve_ax.plot(data["shear_strain"], [t * kpa for t in data["shear_stress"]], "-", lw=1.5)
        curve_ax.set_xlabel("shear strain gamma_xy (-)")
        curve_ax.set_ylabel("shear stress sigma_xy (kPa)")
    else:
        curve_ax.plot([-e for e in data["axial_strain"]], [q * kpa for q in data["q"]], "-",
                      lw=1.5, label="q")
        curve_ax.set_xlabel("axial strain -eps_yy (-, compression positive)")
        curve_ax.set_ylabel("deviatoric stress q (kPa)")
        volume_ax = curve_ax.twinx()
        volume_ax.plot([-e for e in data["axial_strain"]], data["volumetric_strain"], "--",
                       color="tab:orange", lw=1.0, label="volumetric strain")
        volume_ax.set_ylabel("volumetric strain (-, negative in compaction)", color="tab:orange")
    curve_ax.xaxis.set_major_locator(plt.MaxNLocator(5))
    curve_ax.set_title("stress-strain")
    curve_ax.grid(True, alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(target, dpi=120)


if __name__ == "__main__":
    main()
