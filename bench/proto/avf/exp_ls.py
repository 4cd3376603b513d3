"""net-energy at omega_e h = 20 and 100 (10 s, h = 1/60) with full Newton plus backtracking on |R|."""
import sys, time
import numpy as np
import netproto as P

H = 1 / 60
for wh in [float(a) for a in sys.argv[1:]]:
    net = P.Net(10, k=0.01 * (wh / H) ** 2, spread=2.0, lift=1.0)
    P.STATS.clear(); t = time.perf_counter()
    with np.errstate(all="ignore"):
        _, lo, hi = P.run(P.EPC(net, H, "full", linesearch=True), 10.0, energy=True)
    st = P.STATS
    print(f"wh {wh}: {lo:.6f}/{hi:.6f} it/step {st.get('epc_newton', 0) / 600:.2f} cuts {st.get('epc_cuts', 0)} "
          f"nc {st.get('epc_noconv', 0)} ({time.perf_counter() - t:.0f}s)", flush=True)
