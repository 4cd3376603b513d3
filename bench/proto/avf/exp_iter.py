"""(c) iterations a step of the EPC stage solve, net-energy scene, 2 s at h = 1/60:
full Newton (6N LU each iteration), simplified Newton (one 6N LU a step, K at the step start),
one real 3N factor M + h^2 gamma K(x0) as a stationary iteration (gamma: 1/6 minimises the
stiff-end rate |gamma - lambda| / gamma = 0.866; gamma* minimises it at the net's mu_max =
4 (omega_e h)^2) and as GMRES's preconditioner on the full-Newton systems (back-solves counted).
Stop: max position update < TOL."""
import sys
import numpy as np
import netproto as P

H = 1 / 60
T = 2.0
lam = np.linalg.eigvals(P.A2)[0]


def gstar(mu):
    g = np.linspace(0.01, 0.5, 4901)
    r = np.abs(g - lam) * mu / (1 + g * mu)
    return g[np.argmin(r)], r.min()


for tol in [float(a) for a in sys.argv[1:]] or [1e-12, 1e-9]:
    P.TOL = tol
    for wh in [0.3, 0.5, 0.85, 3.0]:
        k = 0.01 * (wh / H) ** 2
        gs, rate = gstar(4 * wh * wh)
        row = [f"tol {tol:g} wh {wh}"]
        for label, mk in [("full", lambda n: P.EPC(n, H, "full")), ("simp", lambda n: P.EPC(n, H, "simp")),
                          ("shift 1/6", lambda n: P.EPC(n, H, "shift", 1 / 6)),
                          (f"shift g*={gs:.3f} (rate {rate:.2f})", lambda n: P.EPC(n, H, "shift", gs)),
                          ("gmres 1/6", lambda n: P.EPC(n, H, "gmres", 1 / 6))]:
            net = P.Net(10, k=k, spread=2.0, lift=1.0)
            S = mk(net)
            P.STATS.clear()
            with np.errstate(all="ignore"):
                _, lo, hi = P.run(S, T, energy=True)
            st = P.STATS; n = round(T / H)
            row.append(f"{label}: it {st.get('epc_newton', 0) / n:.2f} LU6 {st.get('epc_lu6', 0) / n:.2f} "
                       f"LU3 {st.get('epc_lu3', 0) / n:.2f} bsolve3 {st.get('epc_bsolve3', 0) / n:.1f} "
                       f"nc {st.get('epc_noconv', 0)} E {lo:.6f}/{hi:.6f}")
        print(" | ".join(row), flush=True)
