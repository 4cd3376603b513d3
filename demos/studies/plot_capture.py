#!/usr/bin/python3
"""The success map of a net-capture study (docs/sweeps.md): captured or not over the target's
offset and the throw speed, and the success probability against the offset.

Usage: plot_capture.py RESULTS.csv OUT.png  (Debian's /usr/bin/python3 has matplotlib)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(table, picture):
    rows = [r for r in csv.DictReader(open(table)) if r["status"] in ("ok", "warned")]
    offsets = sorted({float(r["offset"]) for r in rows})
    speeds = sorted({abs(float(r["throwSpeed"])) for r in rows})
    grid = [[float("nan")] * len(offsets) for _ in speeds]
    for r in rows:
        grid[speeds.index(abs(float(r["throwSpeed"])))][offsets.index(float(r["offset"]))] = float(
            r["captured"])
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    image = left.imshow(grid, origin="lower", aspect="auto", cmap="RdYlGn", vmin=0, vmax=1,
                        extent=[offsets[0], offsets[-1], speeds[0], speeds[-1]])
    left.set_xlabel("target offset from the net's centre (m)")
    left.set_ylabel("throw speed, downwards (m/s)")
    left.set_title(f"captured (green) or missed: {len(rows)} runs")
    figure.colorbar(image, ax=left)
    rate = [sum(grid[j][i] for j in range(len(speeds))) / len(speeds) for i in range(len(offsets))]
    right.plot(offsets, rate, "o-")
    right.set_xlabel("target offset (m)")
    right.set_ylabel("success probability over throw speeds")
    right.set_ylim(-0.05, 1.05)
    right.grid(True)
    figure.tight_layout()
    figure.savefig(picture, dpi=110)
    captured = sum(float(r["captured"]) for r in rows)
    print(f"{picture}: {int(captured)} of {len(rows)} runs captured")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
