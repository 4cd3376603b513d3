#!/usr/bin/python3
"""Draws the study's figures from the CSV tables tumble-validate --report DIR wrote:
Fig. 4 (oscillator.csv: amplitude and period error of the undamped oscillator against omega h,
beside the discrete theory of semi-implicit Euler) and Fig. 5 (bounce.csv: the first five apex
heights against h, split impulse against Baumgarte). Needs python3-matplotlib.

usage: plot_report.py DIR
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(open(path))]


def fig4(rows, png):
    stable = [r for r in rows if r["omega_h"] < 2 and math.isfinite(r["period_err"])]
    wh = [r["omega_h"] for r in stable]
    theory = [0.02 * i for i in range(1, 100)]  # omega h in (0, 2)
    fig, ax = plt.subplots(figsize=(6, 4.4))
    ax.loglog(wh, [abs(r["ampl_err"]) for r in stable], "o", color="tab:blue",
              label="|amplitude error|, measured")
    ax.loglog(wh, [abs(r["period_err"]) for r in stable], "s", color="tab:red",
              label="|period error|, measured")
    ax.loglog(theory, [1 / math.sqrt(1 - x * x / 4) - 1 for x in theory], "-", color="tab:blue",
              alpha=0.5, label="discrete theory")
    ax.loglog(theory, [x / math.acos(1 - x * x / 2) - 1 for x in theory], "-", color="tab:red",
              alpha=0.5)
    ax.axvline(2, color="k", ls=":", label="omega h = 2: unstable beyond")
    ax.set_xlabel("omega h")
    ax.set_ylabel("relative error")
    ax.set_title("Fig. 4: undamped oscillator, semi-implicit Euler")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def fig5(rows, png):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.4))  # own scales: 1e-4 beside 0.3
    for ax, baumgarte, title in ((axes[0], 0, "split impulse (Tumble's default)"),
                                 (axes[1], 1, "Baumgarte k_erp = 0.2 + restitution")):
        sel = sorted((r for r in rows if r["baumgarte"] == baumgarte), key=lambda r: r["h"])
        for k in range(1, 6):
            pts = [(r["h"], r[f"apex{k}_err"]) for r in sel if math.isfinite(r[f"apex{k}_err"])]
            ax.semilogx([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"apex {k}")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel("h (s)")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes:
        ax.set_ylabel("apex height / analytic - 1")
    axes[0].legend(fontsize=8)
    fig.suptitle("Fig. 5: bounce heights against h (sphere, e = 0.8, from 1 m)")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(out):
    for name, draw, png in (("oscillator", fig4, "fig4_oscillator.png"),
                            ("bounce", fig5, "fig5_bounce.png")):
        path = os.path.join(out, name + ".csv")
        if os.path.exists(path):
            draw(read(path), os.path.join(out, png))
            print(f"wrote {os.path.join(out, png)}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
