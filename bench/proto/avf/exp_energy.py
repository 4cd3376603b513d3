"""(a) net-energy: 10 x 10, 0.01 kg, 5 cm, corners 2 m/s radially, two lifted / two lowered 1 m/s,
k = m (omega_e h / h)^2 at h = 1/60, 10 s. Band set before: min E/E0 >= 0.99, max <= 1.01.
Energy at level n with each scheme's own level velocity (FG: Newmark's; DG: u_n; EPC: v_n)."""
import sys, time
import numpy as np
import netproto as P

H = 1 / 60
T = float(sys.argv[1]) if len(sys.argv) > 1 else 10.0
for wh in [0.1, 0.3, 0.5, 0.7, 0.85, 1.0, 3.0]:
    k = 0.01 * (wh / H) ** 2
    row = [f"{wh:5}"]
    for mk in [lambda n: P.FoxGoodwin(n, H), lambda n: P.MidpointDG(n, H), lambda n: P.EPC(n, H, "full"),
               lambda n: P.EPC(n, H, "shift")]:
        net = P.Net(10, k=k, spread=2.0, lift=1.0)
        S = mk(net)
        P.STATS.clear(); t = time.perf_counter()
        with np.errstate(all="ignore"):
            try:
                _, lo, hi = P.run(S, T, energy=True)
            except Exception as e:
                lo = hi = float("nan")
        st = dict(P.STATS)
        it = st.get("fg_newton", 0) + st.get("dg_newton", 0) + st.get("epc_newton", 0)
        row.append(f"{S.name} {lo:.6f}/{hi:.6f} it/step {it / round(T / H):.2f} nc {st.get('epc_noconv', 0)}"
                   f" ({time.perf_counter() - t:.0f}s)")
    print(" | ".join(row), flush=True)
