#!/usr/bin/env python3
"""compare.png: scored error against wall time, log-log, one line per method.

Usage: compare.py compare.csv compare.png [title]
Each point is one (method, spacing) run, labelled by its spacing and the signed error of its worst
measure, drawn as a triangle pointing up where it over-predicts the reference and down where it
under-predicts it (a circle where the run recorded no sign); a run that doubts its own result
(metrics.json's warnings) is ringed in black, its warnings listed under the chart. Failed runs are
drawn as red crosses on the top edge, numbered, with their reasons listed under the chart, so they
are not dropped and their labels never overlap. Log axes carry labelled ticks at 1, 2 and 5 of every
decade (the error in %). A grid with no scored measure (a scene without references) draws each
measure against spacing and against wall time instead.
"""
import csv
import math
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter  # noqa: E402


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if math.isfinite(value) else None


def spacing_label(text):
    dp = number(text)
    if dp is None:
        return f"dp = {text}"
    return f"dp = {dp * 1000:g} mm" if dp < 0.1 else f"dp = {dp:g} m"


def plain(value, _position=None):
    """A tick label without exponent: 0.002, 0.05, 20, 5000."""
    return f"{value:g}" if 1e-4 <= value < 1e5 else f"{value:.0e}"


def percent(value, _position=None):
    return f"{100 * value:g} %"


def log_axis(axis, formatter):
    axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    axis.set_major_formatter(FuncFormatter(formatter))
    axis.set_minor_formatter(NullFormatter())


def wall_time_limits(ax, rows):
    """x limits around the runs' wall times, at least a decade wide (compare.py, summary.py)."""
    times = [number(r["wall_seconds"]) for r in rows if number(r["wall_seconds"])]
    if times:
        middle = (min(times) * max(times)) ** 0.5
        ax.set_xlim(min(min(times) / 1.5, middle / 3.2), max(max(times) * 1.5, middle * 3.2))


def methods_of(rows):
    methods = []
    for row in rows:
        if row["method"] not in methods:
            methods.append(row["method"])
    return methods


def warnings_of(row):
    """A run's warnings (compare.csv's warning_messages, separated by " | "), or none."""
    return [w for w in (row.get("warning_messages") or "").split(" | ") if w]


def footnote(fig, failed, warned=()):
    """Numbered reasons of the failed runs and the warned runs' warnings under the axes; returns
    the height they take (in)."""
    failed_lines, warned_lines = [], []
    for k, r in enumerate(failed, 1):
        at = number(r.get("failure_time"))
        when = f" at t = {at:.4g} s" if at is not None else ""
        text = f"[{k}] {r['method']} {spacing_label(r['spacing'])}: {r['status']}{when}: " \
               f"{r['failure_reason']}"
        failed_lines.extend(textwrap.wrap(text, 110, subsequent_indent="     "))
    for r in warned:
        for w in warnings_of(r):
            text = f"(!) {r['method']} {spacing_label(r['spacing'])}: {w}"
            warned_lines.extend(textwrap.wrap(text, 110, subsequent_indent="     "))
    if warned_lines:
        fig.text(0.02, 0.01 + 0.16 * len(failed_lines) / 5.2 if failed_lines else 0.01,
                 "\n".join(warned_lines), fontsize=7, va="bottom", ha="left", color="black")
    if failed_lines:
        fig.text(0.02, 0.01, "\n".join(failed_lines), fontsize=7, va="bottom", ha="left",
                 color="darkred")
    lines = len(failed_lines) + len(warned_lines)
    return 0.16 * lines + 0.1 if lines else 0.0


def point_label(row):
    """The run's spacing and its worst measure's signed error."""
    signed = number(row.get("max_signed_error"))
    return spacing_label(row["spacing"]) + (f" ({100 * signed:+.1f} %)" if signed is not None
                                            else "")


def point_marker(row):
    """Up: over the reference; down: under it; a circle where no sign was recorded."""
    signed = number(row.get("max_signed_error"))
    return "o" if signed is None else ("^" if signed > 0 else "v")


def error_chart(rows, target, title):
    methods = methods_of(rows)
    failed = [r for r in rows if r["status"] != "completed"]
    fig, ax = plt.subplots(figsize=(7.0, 5.2))
    finite_errors = [number(r["max_rel_error"]) for r in rows
                     if r["status"] == "completed" and number(r["max_rel_error"])]
    top = max(finite_errors) * 2 if finite_errors else 1.0
    for method in methods:
        runs = [r for r in rows if r["method"] == method]
        ok = [r for r in runs if r["status"] == "completed" and number(r["max_rel_error"])]
        ok.sort(key=lambda r: number(r["wall_seconds"]))
        color = None
        if ok:
            x = [number(r["wall_seconds"]) for r in ok]
            y = [number(r["max_rel_error"]) for r in ok]
            (line,) = ax.plot(x, y, "-", label=method)
            color = line.get_color()
            for r, xi, yi in zip(ok, x, y):
                ax.plot([xi], [yi], point_marker(r), color=color, ms=7)
                if warnings_of(r):
                    ax.plot([xi], [yi], "o", ms=14, mfc="none", mec="black", mew=1.2)
                ax.annotate(point_label(r), (xi, yi), textcoords="offset points",
                            xytext=(5, 4), fontsize=7, color=color)
    for k, r in enumerate(failed, 1):
        x = number(r["wall_seconds"]) or 1e-3
        ax.plot([x], [top], "x", color="red", ms=8, mew=2)
        ax.annotate(f"[{k}]", (x, top), textcoords="offset points", xytext=(0, -13 - 9 * (k % 2)),
                    fontsize=7, color="red", ha="center")
    ax.set_xscale("log")
    ax.set_yscale("log")
    # At least a decade on each axis, so near-equal errors are not blown up into a steep line.
    if finite_errors:
        low, high = min(finite_errors), max(finite_errors)
        middle = (low * high) ** 0.5
        ax.set_ylim(min(low / 2, middle / 3.2), max(top * 1.5, middle * 3.2))
    wall_time_limits(ax, rows)
    log_axis(ax.xaxis, plain)
    log_axis(ax.yaxis, percent)
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("largest relative error of the scored measures")
    ax.set_title(title)
    ax.grid(True, which="major", alpha=0.35)
    if any(ax.get_legend_handles_labels()[1]):
        handles, labels = ax.get_legend_handles_labels()
        signs = {point_marker(r) for r in rows if r["status"] == "completed"}
        for marker, meaning in (("^", "over the reference"), ("v", "under the reference")):
            if marker in signs:
                handles.append(plt.Line2D([], [], ls="none", marker=marker, color="gray"))
                labels.append(meaning)
        if any(warnings_of(r) for r in rows if r["status"] == "completed"):
            handles.append(plt.Line2D([], [], ls="none", marker="o", ms=10, mfc="none",
                                      mec="black"))
            labels.append("warned (listed below)")
        ax.legend(handles, labels, fontsize=8)
    warned = [r for r in rows if r["status"] == "completed" and warnings_of(r)]
    note = footnote(fig, failed, warned)
    fig.tight_layout(rect=(0, min(note / 5.2, 0.5), 1, 1))
    fig.savefig(target, dpi=120)


def measures_chart(rows, target, title):
    """No scored measure: every measure against spacing and against wall time."""
    names = [k for k in rows[0] if k.startswith("measure.")] if rows else []
    methods = methods_of(rows)
    failed = [r for r in rows if r["status"] != "completed"]
    height = 2.8 * max(len(names), 1) + 0.8
    fig, axes = plt.subplots(max(len(names), 1), 2, figsize=(9.0, height), squeeze=False)
    for row_axes, name in zip(axes, names):
        for ax, column, label, formatter in ((row_axes[0], "spacing", "spacing dp (m)", plain),
                                             (row_axes[1], "wall_seconds", "wall time (s)",
                                              plain)):
            for method in methods:
                ok = [r for r in rows if r["method"] == method and r["status"] == "completed"
                      and number(r[name]) is not None and number(r[column])]
                ok.sort(key=lambda r: number(r[column]))
                if ok:
                    ax.plot([number(r[column]) for r in ok], [number(r[name]) for r in ok], "o-",
                            label=method)
            if ax.lines:
                ax.set_xscale("log")
                log_axis(ax.xaxis, formatter)
                ax.legend(fontsize=7)
            ax.set_xlabel(label)
            ax.set_ylabel(name[len("measure."):])
            ax.grid(True, alpha=0.35)
    if not names:
        axes[0][0].text(0.5, 0.5, "no measure recorded", ha="center", va="center")
    fig.suptitle(f"{title}: no scored measure; each measure against spacing and cost",
                 fontsize=10)
    note = footnote(fig, failed)
    fig.tight_layout(rect=(0, min(note / height, 0.5), 1, 0.97))
    fig.savefig(target, dpi=120)


def main():
    source, target = sys.argv[1], sys.argv[2]
    title = sys.argv[3] if len(sys.argv) > 3 else "error against cost"
    with open(source, newline="") as f:
        rows = list(csv.DictReader(f))
    scored = any(r["status"] == "completed" and number(r["max_rel_error"]) is not None
                 for r in rows)
    if scored:
        error_chart(rows, target, title)
    else:
        measures_chart(rows, target, title)


if __name__ == "__main__":
    main()
