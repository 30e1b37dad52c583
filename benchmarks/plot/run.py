#!/usr/bin/env python3
"""The charts of one run, written beside it (duet plot RUN_DIR; duet run draws them at the end).

Usage: run.py RUN_DIR [FIELD]
  series.png              every measure of /series against time
  load_<target>.png       a wall's or rigid body's force against its displacement, when the scene
                          records both as series (a footing: load against settlement), each
                          quantity once (not again in another scale) with its reference curve
  curve_<measure>.png     a measure with at = "curve" against its abscissa, with its reference
                          curve or value and the scored window
  expansion_<target>.png  a radial wall's pressure against a / a0 (a cavity)
  collapse_<body>.png     a body's run-out and height against time (a collapse)
  snapshots_<FIELD>.png   the particles at the first, middle and last frame coloured by FIELD
                          (default von_mises), walls and rigid bodies drawn where they were; the
                          middle frame is mid-flow (the largest kinetic energy) where the motion
                          peaks and dies down within the run, else the frame half way
Prints the files written, one per line. A failed or interrupted run is drawn too, its status and
reason in every title.
"""
import json
import math
import os
import sys
import tomllib

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
import numpy as np  # noqa: E402

UNITS = {  # of a measure kind, before its scale
    "front": "m", "height": "m", "reaction": "N/m", "wall_stress": "Pa",
    "max_displacement": "m", "displacement": "m", "point_displacement": "m", "period": "s",
    "safety_factor": "-", "expansion": "-",
}

FIELD_UNITS = {  # of the one-column frame datasets (common/h5_writer.hpp)
    "pressure": "Pa, compression positive", "von_mises": "Pa", "equivalent_strain": "-",
    "density": "kg/m^3", "mass": "kg/m", "volume": "m^2", "body": "index", "material": "index",
}


def status_line(metrics):
    status = metrics.get("status", "unknown")
    if status == "completed":
        return "completed"
    failure = metrics.get("failure") or {}
    reason = failure.get("reason", "")
    at = failure.get("time", metrics.get("end_time"))
    text = f"{status} at t = {at:.4g} s" if isinstance(at, (int, float)) else status
    return f"{text}: {reason}" if reason else text


def wrap(text, width=90):
    words, lines, line = text.split(), [], ""
    for w in words:
        if len(line) + len(w) + 1 > width and line:
            lines.append(line)
            line = w
        else:
            line = f"{line} {w}".strip()
    if line:
        lines.append(line)
    return "\n".join(lines)


def unit_of(measure):
    unit = UNITS.get(measure.get("kind"), "")
    if measure.get("divide_by"):
        return "-"
    return unit if float(measure.get("scale", 1.0)) == 1.0 else f"{unit} x {measure['scale']:g}"


def schedule_integral(knots, t):
    """Integral from 0 to t of a piecewise-linear schedule [[t, v, ...], ...] (first component)."""
    if not knots:
        return 0.0

    def value(s):
        if s <= knots[0][0]:
            return knots[0][1]
        for a, b in zip(knots, knots[1:]):
            if s <= b[0]:
                w = (s - a[0]) / (b[0] - a[0]) if b[0] > a[0] else 1.0
                return a[1] + w * (b[1] - a[1])
        return knots[-1][1]

    times = sorted({0.0, t} | {k[0] for k in knots if 0.0 < k[0] < t})
    return sum(0.5 * (value(a) + value(b)) * (b - a) for a, b in zip(times, times[1:]))


class Run:
    def __init__(self, folder):
        self.folder = folder
        with open(os.path.join(folder, "metrics.json")) as f:
            self.metrics = json.load(f)
        self.h5 = h5py.File(os.path.join(folder, "run.h5"), "r")
        self.scene = tomllib.loads(self.h5["meta/scene_toml"][()].decode())
        self.series = {k: self.h5["series"][k][()] for k in self.h5["series"]} \
            if "series" in self.h5 else {}
        self.frames = sorted(self.h5["frames"].keys()) if "frames" in self.h5 else []
        self.label = (f"{self.metrics.get('scene', '?')} / {self.metrics.get('method', '?')} / "
                      f"dp = {self.metrics.get('spacing', 0):g} m")
        self.status = status_line(self.metrics)
        self.written = []

    def title(self, fig, what):
        fig.suptitle(wrap(f"{what}: {self.label} ({self.status})"), fontsize=9)

    def save(self, fig, name):
        path = os.path.join(self.folder, name)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        self.written.append(path)


def plot_series(run):
    names = [k for k in run.series if k != "time"]
    if not names or "time" not in run.series:
        return
    measures = run.scene.get("measure", {})
    cols = min(3, len(names))
    rows = math.ceil(len(names) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.0 * rows + 0.6), squeeze=False)
    t = run.series["time"]
    for ax, name in zip(axes.flat, names):
        ax.plot(t, run.series[name], lw=1.2)
        m = measures.get(name, {})
        ax.set_title(f"{name} ({m.get('kind', '?')} of {m.get('target', '-')})", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel(f"{name} ({unit_of(m)})" if m else name)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    run.title(fig, "measures against time")
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    run.save(fig, "series.png")


def same_quantity(a, b):
    """Two measures of one quantity that differ at most in scale and in when they report it (the
    footing's load in N/m and its q / c_u)."""
    return all(a.get(k) == b.get(k) for k in ("kind", "target", "component", "divide_by", "point"))


def scale_of(measure):
    return float(measure.get("scale", 1.0))


def series_of(run, kinds, target):
    """Names of the recorded series of `kinds` on `target`, each quantity once (one measured in two
    scales is drawn once): the one with a reference curve where there is one, else the first in
    the scene's order."""
    measures = run.scene.get("measure", {})
    references = run.scene.get("reference", {})
    out = []
    for name, m in measures.items():
        if m.get("kind") not in kinds or m.get("target") != target or name not in run.series:
            continue
        twin = next((k for k, o in enumerate(out) if same_quantity(measures[o], m)), None)
        if twin is None:
            out.append(name)
        elif "points" in references.get(name, {}) and "points" not in references.get(out[twin], {}):
            out[twin] = name
    return out


def reference_against(run, force, move):
    """The reference curve of `force` (or of a measure of the same quantity) in the units of the
    chart: x as |move|, y as `force`; None where there is none or its abscissa is not `move`'s
    quantity."""
    measures = run.scene.get("measure", {})
    for name, ref in run.scene.get("reference", {}).items():
        m = measures.get(name)
        if m is None or "points" not in ref or not same_quantity(m, measures[force]):
            continue
        a = measures.get(m.get("abscissa", ""))
        if a is None or not same_quantity(a, measures[move]):
            continue
        pts = np.array(ref["points"], dtype=float)
        x = np.abs(pts[:, 0] / scale_of(a) * scale_of(measures[move]))
        y = pts[:, 1] / scale_of(m) * scale_of(measures[force])
        return x, y, ref.get("source", name)
    return None


def force_panels(run, x, xlabel, forces, what, name, move=None):
    """One panel per force measure against `x` (a displacement, a ratio), with its reference curve
    where the scene has one against `move`, saved as `name`."""
    measures = run.scene.get("measure", {})
    fig, axes = plt.subplots(1, len(forces), figsize=(max(5.0 * len(forces), 6.5), 4.2),
                             squeeze=False)
    for ax, force in zip(axes[0], forces):
        ax.plot(x, run.series[force], lw=1.4, label=f"{force} ({run.label})")
        reference = reference_against(run, force, move) if move else None
        if reference is not None:
            ax.plot(reference[0], reference[1], "k--", lw=1.0, label=wrap(reference[2], 60))
            ax.legend(fontsize=7, loc="lower right")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"{force} ({unit_of(measures[force])})")
        ax.grid(alpha=0.3)
    run.title(fig, what)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    run.save(fig, name)


def plot_load_displacement(run):
    targets = list(run.scene.get("rigid_body", {})) + [
        name for name, w in run.scene.get("wall", {}).items() if "radial_velocity" not in w]
    measures = run.scene.get("measure", {})
    for target in targets:
        forces = series_of(run, ("reaction", "wall_stress"), target)
        moves = series_of(run, ("displacement",), target)
        if not forces or not moves:
            continue
        move = moves[0]
        force_panels(run, np.abs(run.series[move]),
                     f"|{move}| (m: {measures[move].get('component', '')} displacement of "
                     f"{target})", forces, f"load against displacement of {target}",
                     f"load_{target}.png", move)


def plot_expansion(run):
    for target, wall in run.scene.get("wall", {}).items():
        if "radial_velocity" not in wall:
            continue
        forces = series_of(run, ("reaction", "wall_stress"), target)
        if not forces or "time" not in run.series:
            continue
        centre = np.array(wall["centre"], dtype=float)
        a0 = float(np.mean([np.linalg.norm(np.array(p) - centre) for p in wall["points"]]))
        ratio = np.array([(a0 + schedule_integral(wall["radial_velocity"], t)) / a0
                          for t in run.series["time"]])
        force_panels(run, ratio, f"a / a0 ({target}, a0 = {a0:.4g} m)", forces,
                     f"expansion of {target}", f"expansion_{target}.png")


def plot_collapse(run):
    if "time" not in run.series:
        return
    for body in run.scene.get("body", {}):
        fronts = series_of(run, ("front",), body)
        heights = series_of(run, ("height",), body)
        if not fronts and not heights:
            continue
        fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8), squeeze=False)
        t = run.series["time"]
        references = run.scene.get("reference", {})
        for ax, names, what in ((axes[0][0], fronts, "run-out"), (axes[0][1], heights, "height")):
            for name in names:
                ax.plot(t, run.series[name], lw=1.4, label=name)
                if name in references:
                    ax.axhline(float(references[name]["value"]), color="k", ls="--", lw=0.8,
                               label=f"{name} reference")
            ax.set_xlabel("time (s)")
            ax.set_ylabel(f"{what} (m)")
            ax.grid(alpha=0.3)
            if names:
                ax.legend(fontsize=8)
        run.title(fig, f"collapse of {body}")
        fig.tight_layout(rect=(0, 0, 1, 0.88))
        run.save(fig, f"collapse_{body}.png")


def plot_curves(run):
    """Each measure with at = "curve" against its abscissa, with its reference (a curve or a
    value) and the scored window shaded; the score from metrics.json in the legend."""
    references = run.scene.get("reference", {})
    accuracy = run.metrics.get("accuracy", {})
    for name, m in run.scene.get("measure", {}).items():
        abscissa = m.get("abscissa")
        if m.get("at") != "curve" or name not in run.series or abscissa not in run.series:
            continue
        fig, ax = plt.subplots(figsize=(6.0, 4.2))
        ax.plot(run.series[abscissa], run.series[name], lw=1.4, label=f"{name} ({run.label})")
        ref = references.get(name, {})
        lo, hi = (float(v) for v in m["x_window"])
        if "points" in ref:
            pts = np.array(ref["points"], dtype=float)
            ax.plot(pts[:, 0], pts[:, 1], "k--", lw=1.0, label=wrap(ref.get("source", ""), 60))
        elif "value" in ref:
            ax.axhline(float(ref["value"]), color="k", ls="--", lw=1.0,
                       label=wrap(ref.get("source", ""), 60))
        ax.axvspan(lo, hi, color="0.85", alpha=0.5, lw=0, label="scored window")
        score = accuracy.get(name, {})
        error = score.get("rel_error")
        if isinstance(error, (int, float)):
            ax.plot([], [], " ", label=f"largest error {100 * error:.3g} % at "
                    f"{abscissa} = {score.get('worst_at', float('nan')):.3g} "
                    f"(signed {100 * score.get('signed_error', float('nan')):+.3g} %)")
        ax.set_xlabel(f"{abscissa} ({unit_of(run.scene['measure'][abscissa])})")
        ax.set_ylabel(f"{name} ({unit_of(m)})")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
        run.title(fig, f"{name} against {abscissa}")
        fig.tight_layout(rect=(0, 0, 1, 0.9))
        run.save(fig, f"curve_{name}.png")


def kinetic_energy(group):
    """The frame's kinetic energy per unit thickness (J/m), from its particles' mass and velocity."""
    if "mass" not in group or "velocity" not in group:
        return float("nan")
    v = group["velocity"][:, :2]
    return 0.5 * float(np.sum(group["mass"][()] * np.sum(v * v, axis=1)))


def middle_frame(run):
    """Mid-flow: the frame of the largest kinetic energy where the motion peaks inside the run and
    dies down by its end (a collapse, a landslide); otherwise the frame half way (a driven footing
    moves at one speed throughout, a static run not at all)."""
    half = len(run.frames) // 2
    energies = [kinetic_energy(run.h5["frames"][name]) for name in run.frames]
    if len(energies) < 3 or not all(math.isfinite(e) for e in energies):
        return half
    peak = int(np.argmax(energies))
    if 0 < peak < len(energies) - 1 and energies[-1] < 0.5 * energies[peak]:
        return peak
    return half


def frame_time(run, k):
    return float(run.h5["frames"][run.frames[k]].attrs["time"])


def nearest_frame(run, t):
    """The index of the run's frame nearest time t."""
    return min(range(len(run.frames)), key=lambda k: abs(frame_time(run, k) - t))


def snapshot_frames(run, field, middle=None):
    """The first, middle and last frames of a run (h5 groups), checked to hold `field`; the
    middle one is mid-flow (middle_frame) unless given (an index)."""
    middle = middle_frame(run) if middle is None else middle
    picks = sorted({0, middle, len(run.frames) - 1})
    groups = [run.h5["frames"][run.frames[k]] for k in picks]
    if field not in groups[0] or not isinstance(groups[0][field], h5py.Dataset):
        n = groups[0]["position"].shape[0]
        available = [k for k, v in groups[0].items()
                     if isinstance(v, h5py.Dataset) and v.shape == (n,) and k != "vertices"]
        # "run.py: " marks a user's mistake: `duet plot` says it as an input error (exit 2)
        raise SystemExit(f"run.py: no field '{field}' in the frames; one of "
                         f"{', '.join(available)}")
    return groups


def colour_range(groups, field):
    """The 1st to 99th percentile of the field over the frames (one outlier does not wash out the
    rest)."""
    values = [g[field][()] for g in groups]
    finite = np.concatenate([v[np.isfinite(v)] for v in values]) if values else np.array([])
    lo, hi = (np.percentile(finite, 1), np.percentile(finite, 99)) if finite.size else (0, 1)
    return (lo, hi if hi > lo else lo + 1.0)


def extent(groups, spacing):
    """x and y limits holding every particle and boundary of the frames, a spacing around."""
    everything = np.concatenate([g["position"][:, :2] for g in groups] +
                                [g["boundary_points"][:, :2] for g in groups
                                 if "boundary_points" in g])
    (xmin, ymin), (xmax, ymax) = everything.min(axis=0) - spacing, everything.max(axis=0) + spacing
    return xmin, xmax, ymin, ymax


def draw_frame(fig, ax, g, field, spacing, limits, colours):
    """One frame: a square marker per particle the size of its cell, coloured on `colours` (lo,
    hi), walls and rigid bodies where they were."""
    xmin, xmax, ymin, ymax = limits
    x = g["position"][:, :2]
    ax.set_xlim(xmin, xmax)
    points_per_metre = ax.get_window_extent().width / (xmax - xmin) * 72 / fig.dpi
    size = max((spacing * points_per_metre) ** 2, 0.25)
    art = ax.scatter(x[:, 0], x[:, 1], c=g[field][()], s=size, marker="s", cmap="viridis",
                     vmin=colours[0], vmax=colours[1], linewidths=0)
    if "boundary_points" in g:
        p = g["boundary_points"][:, :2]
        segments = [[p[a], p[b]] for a, b in g["boundary_segments"][()]]
        ax.add_collection(LineCollection(segments, colors="k", linewidths=1.6))
    ax.set_xlim(xmin, xmax)
    ax.set_ylim(ymin, ymax)
    ax.set_aspect("equal")
    ax.set_title(f"t = {float(g.attrs['time']):.4g} s", fontsize=9)
    ax.set_xlabel("x (m)")
    return art


def field_label(field):
    unit = FIELD_UNITS.get(field)
    return f"{field} ({unit})" if unit else field


def plot_snapshots(run, field):
    if not run.frames:
        return
    groups = snapshot_frames(run, field)
    spacing = float(run.h5["meta"].attrs["spacing"])
    limits = extent(groups, spacing)
    xmin, xmax, ymin, ymax = limits
    aspect = min(max((ymax - ymin) / max(xmax - xmin, 1e-12), 0.25), 2.0)
    panel = 4.0
    fig, axes = plt.subplots(1, len(groups), figsize=(panel * len(groups) + 1.2,
                                                      panel * aspect + 1.3),
                             squeeze=False, layout="constrained")
    fig.canvas.draw()  # lay out first: the marker size needs the axes' size
    colours = colour_range(groups, field)
    for ax, g in zip(axes[0], groups):
        art = draw_frame(fig, ax, g, field, spacing, limits, colours)
    axes[0][0].set_ylabel("y (m)")
    fig.colorbar(art, ax=list(axes[0]), shrink=0.9, label=field_label(field))
    run.title(fig, f"{field}")
    run.save(fig, f"snapshots_{field}.png")


def main():
    if len(sys.argv) < 2:
        raise SystemExit(__doc__)
    run = Run(sys.argv[1])
    field = sys.argv[2] if len(sys.argv) > 2 else "von_mises"
    plot_series(run)
    plot_load_displacement(run)
    plot_curves(run)
    plot_expansion(run)
    plot_collapse(run)
    plot_snapshots(run, field)
    for path in run.written:
        print(path)


if __name__ == "__main__":
    main()
