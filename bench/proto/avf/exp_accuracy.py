"""(b) net-10 sweep scene (bench/harness/sweep_scenes.cpp netModel): 10 x 10, 0.01 kg, 5 cm,
k = 400 N/m, thrown open in free space at 0.5 m/s at the corners, 1.2 s; error = largest node
position difference from the reference, sampled every 0.1 s (as tumble-bench --sweep).
Reference: velocity Verlet at 1e-5 s (self-error against 5e-6 s printed)."""
import time
import numpy as np
import netproto as P

T, SAMPLE = 1.2, 0.1
net = P.Net(10, k=400.0, spread=0.5)
t = time.perf_counter()
ref = P.verlet(net, 1e-5, T, SAMPLE)
ref2 = P.verlet(net, 5e-6, T, SAMPLE)
print(f"reference self-error (1e-5 vs 5e-6): {np.abs(ref - ref2).max():.2e} m ({time.perf_counter() - t:.0f}s)")
ref = ref2
for hinv in [60, 120, 240, 480, 1000]:
    h = 1 / hinv
    row = [f"1/{hinv} (omega_e h {200 * h:.3f})"]
    for S in [P.FoxGoodwin(net, h), P.MidpointDG(net, h), P.EPC(net, h, "full")]:
        P.STATS.clear()
        with np.errstate(all="ignore"):
            out, _, _ = P.run(S, T, SAMPLE)
        err = np.linalg.norm(out - ref, axis=2).max()
        st = P.STATS
        it = st.get("fg_newton", 0) + st.get("dg_newton", 0) + st.get("epc_newton", 0)
        row.append(f"{S.name} {err:.3e} ({it / round(T / h):.2f} it/step)")
    print(" | ".join(row), flush=True)
