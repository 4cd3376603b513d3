#!/usr/bin/python3
"""Draws the study's figures from the CSV tables tumble-validate --report DIR wrote:
Fig. 4 (oscillator.csv: amplitude and period error of the undamped oscillator against omega h,
beside the discrete theory of semi-implicit Euler) and Fig. 5 (bounce.csv: the first five apex
heights against h, split impulse against Baumgarte), Fig. 7 (string-transient.csv,
string-spectrum.csv, string.csv: the struck hanging string's transient and spectrum with the
chain's modes marked), Fig. 10 (string-cost.csv: cost per simulated second against EA, explicit
at h = 0.9 / omega_e and implicit at fixed h) and Fig. 11 (stack-cost.csv, and fig11_peers.csv
when tumble-bench's results are there: cost per simulated second against the number of cubes).
Fig. 7 and Fig. 10 add the peers' string from string-peers-{transient,cost}.csv when present,
Fig. 4 and Fig. 5 the peers' oscillator and bounce from study-peers-{oscillator,bounce}.csv.
Needs python3-matplotlib.

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


def fig4(rows, png, out):
    stable = [r for r in rows if r["omega_h"] < 2 and math.isfinite(r["period_err"])]
    wh = [r["omega_h"] for r in stable]
    theory = [0.02 * i for i in range(1, 100)]  # omega h in (0, 2)
    fig, ax = plt.subplots(figsize=(6, 4.4))
    ax.loglog(wh, [abs(r["ampl_err"]) for r in stable], "o", color="tab:blue",
              label="|amplitude error|, Tumble")
    ax.loglog(wh, [abs(r["period_err"]) for r in stable], "s", color="tab:red",
              label="|period error|, Tumble")
    ax.loglog(theory, [1 / math.sqrt(1 - x * x / 4) - 1 for x in theory], "-", color="tab:blue",
              alpha=0.5, label="discrete theory")
    ax.loglog(theory, [x / math.acos(1 - x * x / 2) - 1 for x in theory], "-", color="tab:red",
              alpha=0.5)
    peers = read_peers(os.path.join(out, "study-peers-oscillator.csv"))
    for engine, points in peers.items():
        color, _ = PEER_STYLE.get(engine, ("tab:gray", "-."))
        kept = [p for p in points if p["omega_h"] < 2 and math.isfinite(p["period_err"])]
        ax.loglog([p["omega_h"] for p in kept], [abs(p["ampl_err"]) for p in kept], "x",
                  color=color, ms=7, label=f"{NAME.get(engine, engine)}: |amplitude error|")
        ax.loglog([p["omega_h"] for p in kept], [abs(p["period_err"]) for p in kept], "+",
                  color=color, ms=8, label=f"{NAME.get(engine, engine)}: |period error|")
    ax.axvline(2, color="k", ls=":", label="omega h = 2: unstable beyond")
    ax.set_xlabel("omega h")
    ax.set_ylabel("relative error")
    ax.set_title("Fig. 4: undamped oscillator, semi-implicit Euler")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def worst_reached(row):
    """The largest |apex error| among the apexes reached, and whether all five were."""
    errs = [row[f"apex{k}_err"] for k in range(1, 6)]
    reached = [abs(e) for e in errs if math.isfinite(e)]
    return (max(reached) if reached else math.nan), len(reached) == len(errs)


def side(rows):
    """' (all above analytic)' or ' (all below)' when every apex reached is, else ''."""
    errs = [r[f"apex{k}_err"] for r in rows for k in range(1, 6)]
    errs = [e for e in errs if math.isfinite(e)]
    if errs and all(e > 0 for e in errs):
        return " (all above analytic)"
    return " (all below)" if errs and all(e < 0 for e in errs) else ""


# tumble-bench --study's bounce variants: (engine, correction, speculative) -> label, style.
BOUNCE_PEERS = (
    (("bullet", "default", 1), "Bullet (harness), its default", ("tab:green", "-", "^")),
    (("bullet", "baumgarte", 1), "Bullet (harness), Baumgarte", ("tab:green", "--", "v")),
    (("bullet", "split_impulse", 1), "Bullet (harness), split impulse", ("tab:green", ":", "D")),
    (("bullet", "baumgarte", 0), "Bullet (harness), Baumgarte, touching contacts only",
     ("tab:olive", "--", "v")),
    (("bullet", "split_impulse", 0), "Bullet (harness), split impulse, touching contacts only",
     ("tab:olive", ":", "D")),
    (("ode", "default", 1), "ODE (harness), Baumgarte (ERP 0.2)", ("tab:purple", "-.", "s")),
)


def fig5(rows, png, out):
    peers = read_peers(os.path.join(out, "study-peers-bounce.csv"))
    fig, axes = plt.subplots(1, 3 if peers else 2, figsize=(18 if peers else 10, 4.6))
    for ax, baumgarte, title in ((axes[0], 0, "Tumble, split impulse (its default)"),
                                 (axes[1], 1, "Tumble, Baumgarte k_erp = 0.2 + restitution")):
        sel = sorted((r for r in rows if r["baumgarte"] == baumgarte), key=lambda r: r["h"])
        for k in range(1, 6):
            pts = [(r["h"], r[f"apex{k}_err"]) for r in sel if math.isfinite(r[f"apex{k}_err"])]
            ax.semilogx([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"apex {k}")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel("h (s)")
        ax.set_ylabel("apex height / analytic - 1")
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    if peers:
        # The peers' errors span 1e-4 to 1: the worst apex on log axes, beside Tumble's.
        ax = axes[2]
        for baumgarte, label, color in ((0, "Tumble, split impulse", "tab:blue"),
                                        (1, "Tumble, Baumgarte", "tab:orange")):
            sel = sorted((r for r in rows if r["baumgarte"] == baumgarte), key=lambda r: r["h"])
            ax.loglog([r["h"] for r in sel], [worst_reached(r)[0] for r in sel], "o-",
                      color=color, lw=2, label=label + side(sel))
        short = []
        for (engine, correction, speculative), label, (color, style, marker) in BOUNCE_PEERS:
            sel = sorted((r for r in peers.get(engine, [])
                          if r["correction"] == correction and r["speculative"] == speculative),
                         key=lambda r: r["h"])
            if not sel:
                continue
            worst = [worst_reached(r) for r in sel]
            ax.loglog([r["h"] for r in sel], [w[0] for w in worst], marker, ls=style,
                      color=color, label=label + side(sel))
            short += [(r["h"], w[0]) for r, w in zip(sel, worst) if not w[1]]
        ax.plot([p[0] for p in short], [p[1] if math.isfinite(p[1]) else 1 for p in short],
                "kx", ms=10, label="fewer than 5 apexes: the ball stopped bouncing")
        ax.set_xlabel("h (s)")
        ax.set_ylabel("worst |apex height / analytic - 1| of the first 5")
        ax.set_title("beside the peers (tumble-bench --study)", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1))
    fig.suptitle("Fig. 5: bounce heights against h (sphere, e = 0.8, from 1 m)")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def number_or_text(v):
    try:
        return float(v)
    except ValueError:
        return v


def read_peers(path):
    """tumble-bench --string's or --study's rows by engine (text columns kept as text); {} when
    absent."""
    if not os.path.exists(path):
        return {}
    peers = {}
    for row in csv.DictReader(open(path)):
        engine = row.pop("engine")
        peers.setdefault(engine, []).append({k: number_or_text(v) for k, v in row.items()})
    return peers


PEER_STYLE = {"bullet": ("tab:green", "--"), "ode": ("tab:purple", ":")}
# The peers' runs come from tumble-bench, not from this report's run.
NAME = {"bullet": "Bullet (harness)", "ode": "ODE (harness)"}


def windowed_spectrum(x, dt, omegas):
    """|Hann-windowed DTFT| of x at each omega: validation/cases/lumped.h's windowedSpectrum."""
    import numpy as np
    x = np.asarray(x)
    n = len(x)
    w = 0.5 - 0.5 * np.cos(2 * np.pi * np.arange(n) / (n - 1))
    k = np.arange(n)
    return [abs(np.sum(w * x * np.exp(-1j * omega * dt * k))) for omega in omegas]


def fig7(out, png):
    transient = read(os.path.join(out, "string-transient.csv"))
    spectrum = read(os.path.join(out, "string-spectrum.csv"))
    modes = read(os.path.join(out, "string.csv"))
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7))
    t = [r["t"] for r in transient]
    top.plot(t, [100 * r["x_node14_m"] for r in transient], lw=1, label="node 14 (struck)")
    top.plot(t, [100 * r["x_end_m"] for r in transient], lw=1, label="node 29 (free end)")
    peers = read_peers(os.path.join(out, "string-peers-transient.csv"))
    for engine, rows in peers.items():
        color, style = PEER_STYLE.get(engine, ("tab:gray", "-."))
        early = [r for r in rows if r["t"] <= max(t) + 1e-9]
        top.plot([r["t"] for r in early], [100 * r["x_end_m"] for r in early], lw=0.9,
                 color=color, ls=style, label=f"free end, {engine} (point masses, harness threads)")
    top.set_xlabel("t (s)")
    top.set_ylabel("transverse displacement x (cm)")
    top.set_title("transient (explicit threads, h = 5e-4 s)")
    top.grid(True, alpha=0.3)
    top.legend(fontsize=8)
    w = [r["omega"] for r in spectrum]
    peak = max(max(r["node14"] for r in spectrum), max(r["end"] for r in spectrum))
    bottom.semilogy(w, [r["node14"] / peak for r in spectrum], lw=1, label="node 14 (struck)")
    bottom.semilogy(w, [r["end"] / peak for r in spectrum], lw=1, label="node 29 (free end)")
    tumble_dt = t[1] - t[0]
    for engine, rows in peers.items():
        color, style = PEER_STYLE.get(engine, ("tab:gray", "-."))
        dt = rows[1]["t"] - rows[0]["t"]
        # Scaled by dt / Tumble's dt: the DTFT sums samples, and the records are sampled apart.
        spectrum = windowed_spectrum([r["x_end_m"] for r in rows], dt, w)
        bottom.semilogy(w, [v * dt / tumble_dt / peak for v in spectrum], lw=0.9, color=color,
                        ls=style, label=f"free end, {engine}")
    for i, m in enumerate(modes):
        bottom.axvline(m["omega_lumped"], color="k", lw=0.8,
                       label="lumped chain's modes (linearised)" if i == 0 else None)
        bottom.axvline(m["omega_continuous"], color="tab:red", ls=":", lw=1,
                       label="continuous chain: (j0,n / 2) sqrt(g / L)" if i == 0 else None)
    bottom.set_xlim(0, max(w))
    bottom.set_ylim(1e-5, 2)
    bottom.set_xlabel("omega (rad/s)")
    bottom.set_ylabel("|Hann-windowed DTFT| (normalised)")
    bottom.set_title("spectrum of the whole record")
    bottom.grid(True, which="both", alpha=0.3)
    bottom.legend(fontsize=8, loc="upper right")
    fig.suptitle("Fig. 7: hanging string of 30 masses, node 14 struck sideways at 2 m/s")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def fig10(out, png):
    rows = read(os.path.join(out, "string-cost.csv"))
    ea = [r["EA_N"] for r in rows]
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    ax.loglog(ea, [r["explicit_cpu_s_per_s"] for r in rows], "o-", color="tab:red",
              label="explicit, h = 0.9 / omega_e (CPU)")
    ax.loglog(ea, [r["explicit_wall_s_per_s"] for r in rows], "x", color="tab:red", alpha=0.6,
              label="explicit (wall)")
    h = rows[0]["implicit_h"]
    ax.loglog(ea, [r["implicit_cpu_s_per_s"] for r in rows], "s-", color="tab:blue",
              label=f"implicit, h = {h:g} s (CPU)")
    ax.loglog(ea, [r["implicit_wall_s_per_s"] for r in rows], "x", color="tab:blue", alpha=0.6,
              label="implicit (wall)")
    peers = read_peers(os.path.join(out, "string-peers-cost.csv"))
    for engine, points in peers.items():
        color, style = PEER_STYLE.get(engine, ("tab:gray", "-."))
        ax.loglog([p["EA_N"] for p in points], [p["cpu_s_per_s"] for p in points], "^",
                  ls=style, color=color,
                  label=f"{engine}: point masses, harness threads, h = 0.9 / omega_e (CPU)")
    anchor = rows[0]["explicit_cpu_s_per_s"]
    ax.loglog(ea, [anchor * math.sqrt(x / ea[0]) for x in ea], "k--", lw=0.8,
              label="~ sqrt(EA)")
    ax.set_xlabel("EA (N)  [k = EA / 0.05 m per segment]")
    ax.set_ylabel("time per simulated second (s)")
    ax.set_title("Fig. 10: string cost against stiffness (30 masses)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def fig11(out, png):
    rows = read(os.path.join(out, "stack-cost.csv"))
    n = [r["cubes"] for r in rows]
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    med = [r["wall_s_per_s"] for r in rows]
    ax.errorbar(n, med, yerr=[[m - r["wall_min"] for m, r in zip(med, rows)],
                              [r["wall_max"] - m for m, r in zip(med, rows)]],
                fmt="o-", color="tab:blue", capsize=3, label="Tumble, this run (median, min-max)")
    peers = os.path.join(out, "fig11_peers.csv")
    if os.path.exists(peers):
        bench = list(csv.DictReader(open(peers)))
        styles = {"tumble": "tab:blue", "bullet": "tab:red", "ode": "tab:green",
                  "box2d": "tab:purple"}
        for engine, color in styles.items():
            pts = sorted((float(r["cubes"]), float(r["wall_s_per_s"]), float(r["collapsed_at_s"]))
                         for r in bench if r["engine"] == engine)
            if pts:
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "^--", color=color, alpha=0.8,
                        label=f"{engine}, tumble-bench run")
                fell = [p for p in pts if p[2] >= 0]
                ax.plot([p[0] for p in fell], [p[1] for p in fell], "x", color="k", ms=9,
                        label="collapsed during the run" if engine == "ode" else None)
    ax.set_xlabel("cubes in the column N")
    ax.set_ylabel("wall time per simulated second (s)")
    ax.set_title("Fig. 11: stack cost against N (h = 1/60, 10 iterations)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(out):
    for name, draw, png in (("oscillator", fig4, "fig4_oscillator.png"),
                            ("bounce", fig5, "fig5_bounce.png")):
        path = os.path.join(out, name + ".csv")
        if os.path.exists(path):
            draw(read(path), os.path.join(out, png), out)
            print(f"wrote {os.path.join(out, png)}")
    for name, draw, png in (("string-spectrum", fig7, "fig7_string.png"),
                            ("string-cost", fig10, "fig10_string_cost.png"),
                            ("stack-cost", fig11, "fig11_stack_cost.png")):
        if os.path.exists(os.path.join(out, name + ".csv")):
            draw(out, os.path.join(out, png))
            print(f"wrote {os.path.join(out, png)}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
