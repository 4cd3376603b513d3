"""(c) the one-real-factor block Gauss-Seidel ('tri') against simplified Newton ('simp', exact
2x2 coupling, the count the complex diagonalisation would need) and full Newton, K frozen at the
step start or at the predictor's midpoint; net-energy scene 10 x 10 (2 s) or 40 x 40 (1 s),
h = 1/60, tol 1e-9 m."""
import sys, time
import numpy as np
import netproto as P

H = 1 / 60
P.TOL = 1e-9
n = int(sys.argv[1]); T = float(sys.argv[2])
for wh in [float(a) for a in sys.argv[3:]]:
    row = [f"{n}x{n} wh {wh}"]
    for label, mk in [("simp x0", lambda q: P.EPC(q, H, "simp")), ("simp mid", lambda q: P.EPC(q, H, "simp", kat="mid")),
                      ("tri x0", lambda q: P.EPC(q, H, "tri")), ("tri mid", lambda q: P.EPC(q, H, "tri", kat="mid")),
                      ("tri mid g.065 l.29", lambda q: P.EPC(q, H, "tri", 0.065, 0.29, "mid"))]:
        net = P.Net(n, k=0.01 * (wh / H) ** 2, spread=2.0, lift=1.0)
        P.STATS.clear(); t = time.perf_counter()
        with np.errstate(all="ignore"):
            _, lo, hi = P.run(mk(net), T, energy=True)
        st = P.STATS; ns = round(T / H)
        row.append(f"{label}: it {st.get('epc_newton', 0) / ns:.2f} nc {st.get('epc_noconv', 0)} E {lo:.6f}/{hi:.6f}")
    print(" | ".join(row), flush=True)
