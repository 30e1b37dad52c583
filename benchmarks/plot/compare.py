#!/usr/bin/env python3
"""compare.png: scored error against wall time, log-log, one line per method.

Usage: compare.py compare.csv compare.png [title]
Each point is one (method, spacing) run, labelled by its spacing; failed runs are drawn as red
crosses on the top edge, numbered, with their reasons listed under the chart, so they are not
dropped and their labels never overlap. Log axes carry labelled ticks at 1, 2 and 5 of every
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


def footnote(fig, failed):
    """Numbered reasons of the failed runs under the axes; returns the height they take (in)."""
    if not failed:
        return 0.0
    lines = []
    for k, r in enumerate(failed, 1):
        at = number(r.get("failure_time"))
        when = f" at t = {at:.4g} s" if at is not None else ""
        text = f"[{k}] {r['method']} {spacing_label(r['spacing'])}: {r['status']}{when}: " \
               f"{r['failure_reason']}"
        lines.extend(textwrap.wrap(text, 110, subsequent_indent="     "))
    fig.text(0.02, 0.01, "\n".join(lines), fontsize=7, va="bottom", ha="left", color="darkred")
    return 0.16 * len(lines) + 0.1


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
            (line,) = ax.plot(x, y, "o-", label=method)
            color = line.get_color()
            for r, xi, yi in zip(ok, x, y):
                ax.annotate(spacing_label(r["spacing"]), (xi, yi), textcoords="offset points",
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
        ax.legend()
    note = footnote(fig, failed)
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
