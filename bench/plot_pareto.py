#!/usr/bin/python3
"""Plots tumble-bench --sweep's sweep.csv: wall time per simulated second against error, one panel
per scene, every run faint and each engine's Pareto front drawn through. Needs python3-matplotlib.

usage: plot_pareto.py sweep.csv pareto.png
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"tumble": "tab:blue", "bullet": "tab:red", "ode": "tab:green", "box2d": "tab:orange"}
FLOOR = 1e-16  # (m): errors at or below round-off are drawn here on the log axis


def main(csv_path, png_path):
    rows = list(csv.DictReader(open(csv_path)))
    scenes = sorted({r["scene"] for r in rows})
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.2 * len(scenes), 4.4), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        for engine in sorted({r["engine"] for r in rows if r["scene"] == scene}):
            pts = [r for r in rows if r["scene"] == scene and r["engine"] == engine
                   and r["reference"] == "0"]
            colour = COLOURS.get(engine, "k")
            finite = [r for r in pts if math.isfinite(float(r["error_m"]))]
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
        ax.set_title(scene)
        ax.set_xlabel("wall s per simulated s")
        ax.set_ylabel("error (m)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)
    print(f"wrote {png_path}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
