#!/usr/bin/python3
"""Plots tumble-bench --sweep's sweep.csv: wall time per simulated second against error, one panel
per scene, every sound run faint and each engine's Pareto front drawn through. Runs that collapsed
or blew up have no error to plot: they are crosses on the panel's top edge, at their cost.
Needs python3-matplotlib.

usage: plot_pareto.py sweep.csv pareto.png
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.transforms import blended_transform_factory  # noqa: E402

COLOURS = {"tumble": "tab:blue", "tumble-explicit": "tab:purple", "bullet": "tab:red", "ode": "tab:green", "box2d": "tab:orange"}
FLOOR = 1e-16  # (m): errors at or below round-off are drawn here on the log axis


def main(csv_path, png_path):
    with open(csv_path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    scenes = sorted({r["scene"] for r in rows})
    columns = min(len(scenes), 2)
    lines = (len(scenes) + columns - 1) // columns
    fig, axes = plt.subplots(lines, columns, figsize=(6.4 * columns, 4.8 * lines), squeeze=False)
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    for ax, scene in zip(axes.flat, scenes):
        top_edge = blended_transform_factory(ax.transData, ax.transAxes)
        for engine in sorted({r["engine"] for r in rows if r["scene"] == scene}):
            pts = [r for r in rows if r["scene"] == scene and r["engine"] == engine]
            colour = COLOURS.get(engine, "k")
            finite = [r for r in pts if r["status"] == "ok"]
            unsound = [r for r in pts if r["status"] != "ok"]
            if unsound:
                ax.scatter([float(r["wall_s_per_sim_s"]) for r in unsound], [0.97] * len(unsound),
                           transform=top_edge, marker="x", s=18, color=colour, alpha=0.6,
                           label=f"{engine}: collapsed / blew up")
            ax.scatter([float(r["wall_s_per_sim_s"]) for r in finite],
                       [max(float(r["error_m"]), FLOOR) for r in finite],
                       s=10, alpha=0.3, color=colour)
            front = sorted((r for r in finite if r["pareto"] == "1"),
                           key=lambda r: float(r["wall_s_per_sim_s"]))
            ax.step([float(r["wall_s_per_sim_s"]) for r in front],
                    [max(float(r["error_m"]), FLOOR) for r in front],
                    where="post", color=colour, marker="o", ms=4, label=f"{engine} front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        # Head room for the crosses of the unsound runs along the top edge.
        low, high = ax.get_ylim()
        ax.set_ylim(low, high * 6)
        ax.set_title(scene)
        ax.set_xlabel("wall s per simulated s")
        ax.set_ylabel("error (m)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {png_path}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
