"""(c) 'tri mid' (one real factor, block Gauss-Seidel, K at the predictor's midpoint) at looser
Newton tolerances: iterations a step and the net-energy band (n x n, T s, h = 1/60)."""
import sys, time
import numpy as np
import netproto as P

H = 1 / 60
n = int(sys.argv[1]); T = float(sys.argv[2])
for wh in [float(a) for a in sys.argv[3:]]:
    row = [f"{n}x{n} wh {wh}"]
    for tol in [1e-9, 1e-7, 1e-6, 1e-5]:
        P.TOL = tol
        net = P.Net(n, k=0.01 * (wh / H) ** 2, spread=2.0, lift=1.0)
        P.STATS.clear(); t = time.perf_counter()
        with np.errstate(all="ignore"):
            _, lo, hi = P.run(P.EPC(net, H, "tri", kat="mid"), T, energy=True)
        st = P.STATS; ns = round(T / H)
        row.append(f"tol {tol:g}: it {st.get('epc_newton', 0) / ns:.2f} E {lo:.6f}/{hi:.6f} ({time.perf_counter() - t:.0f}s)")
    print(" | ".join(row), flush=True)
