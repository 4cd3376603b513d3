"""(b) with the one-real-factor Gauss-Seidel stage solve at loose tolerances: the net-10 error
(does the cheap solve keep the fourth-order errors?)."""
import numpy as np
import netproto as P

net = P.Net(10, k=400.0, spread=0.5)
ref = P.verlet(net, 5e-6, 1.2, 0.1)
for hinv in [240, 480, 1000]:
    row = [f"1/{hinv}"]
    for tol in [1e-9, 1e-7, 1e-6, 1e-5]:
        P.TOL = tol
        P.STATS.clear()
        out, _, _ = P.run(P.EPC(net, 1 / hinv, "tri", kat="mid"), 1.2, 0.1)
        row.append(f"tol {tol:g}: {np.linalg.norm(out - ref, axis=2).max():.3e} "
                   f"({P.STATS.get('epc_newton', 0) / round(1.2 * hinv):.2f} it/step)")
    print(" | ".join(row), flush=True)
