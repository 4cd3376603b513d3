"""(c) 40 x 40 net at h = 1/60: the net-energy throw (corners 2 m/s radially, two lifted, two
lowered 1 m/s), omega_e h = 0.5, 1 s; EPC iterations a step by solve variant, tol 1e-9 m, and the
prototype's own factor time against the midpoint discrete gradient's."""
import sys, time
import numpy as np
import netproto as P

H = 1 / 60
T = 1.0
P.TOL = 1e-9
wh = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
gs = {0.3: 0.044, 0.5: 0.047, 0.85: 0.055}.get(wh, 1 / 6)
for label, mk in [("midpoint-dg", lambda n: P.MidpointDG(n, H)), ("epc full", lambda n: P.EPC(n, H, "full")),
                  ("epc simp", lambda n: P.EPC(n, H, "simp")), (f"epc shift {gs}", lambda n: P.EPC(n, H, "shift", gs))]:
    net = P.Net(40, k=0.01 * (wh / H) ** 2, spread=2.0, lift=1.0)
    P.STATS.clear(); t = time.perf_counter()
    with np.errstate(all="ignore"):
        _, lo, hi = P.run(mk(net), T, energy=True)
    st = P.STATS; n = round(T / H)
    it = st.get("epc_newton", 0) + st.get("dg_newton", 0)
    lut = st.get("epc_lu6_t", 0) + st.get("epc_lu3_t", 0) + st.get("dg_lu_t", 0)
    lun = st.get("epc_lu6", 0) + st.get("epc_lu3", 0) + st.get("dg_lu", 0)
    print(f"40x40 wh {wh} {label}: it/step {it / n:.2f}, LU/step {lun / n:.2f}, LU ms each {1e3 * lut / max(lun, 1):.1f}, "
          f"back-solves3/step {st.get('epc_bsolve3', 0) / n:.1f}, E {lo:.6f}/{hi:.6f} nc {st.get('epc_noconv', 0)} "
          f"({time.perf_counter() - t:.0f}s)", flush=True)
