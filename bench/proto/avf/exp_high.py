"""Extra: net-energy at omega_e h = 7, 20, 100 (EPC, full Newton, 10 s) and the net-10 error at
1/2000 (engine: 2.65e-6 m, peers 2.93e-4 m)."""
import time
import numpy as np
import netproto as P

H = 1 / 60
for wh in [7.0, 20.0, 100.0]:
    net = P.Net(10, k=0.01 * (wh / H) ** 2, spread=2.0, lift=1.0)
    P.STATS.clear(); t = time.perf_counter()
    with np.errstate(all="ignore"):
        _, lo, hi = P.run(P.EPC(net, H, "full"), 10.0, energy=True)
    print(f"net-energy wh {wh}: epc-full {lo:.6f}/{hi:.6f} it/step {P.STATS.get('epc_newton', 0) / 600:.2f}"
          f" nc {P.STATS.get('epc_noconv', 0)} ({time.perf_counter() - t:.0f}s)", flush=True)
net = P.Net(10, k=400.0, spread=0.5)
ref = P.verlet(net, 5e-6, 1.2, 0.1)
out, _, _ = P.run(P.EPC(net, 1 / 2000, "full"), 1.2, 0.1)
print(f"net-10 1/2000 epc-full {np.linalg.norm(out - ref, axis=2).max():.3e}", flush=True)
