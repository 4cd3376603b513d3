"""(c) factor cost on a 40 x 40 (and 10 x 10) net, every thread taut (stretched 5 %, rippled out
of plane: geometric stiffness on), h = 1/60, omega_e h = 0.5. scipy SuperLU, one ordering rule
for all (MMD on A' + A, no pivoting: Cholesky's fill, LU's flops), best of 5.
Primal (node space, 3N): the midpoint / implicit Euler system M + h^2 c K; EPC's full stage
system (6N, 2x2 blocks A^2 coupling, unsymmetric); its one complex 3N system M + h^2 lambda K
(lambda an eigenvalue of A^2); the real shift M + h^2 gamma K.
Dual (thread rows, E, what the engine's spring block factors): J M^-1 J' + Gamma, and the
two-stage version (2E, 2x2 coupled by A^-2: unsymmetric)."""
import sys, time
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
import netproto as P


def best(A, reps=5):
    t = []
    for _ in range(reps):
        s = time.perf_counter()
        lu = spla.splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0,
                       options=dict(SymmetricMode=True))
        t.append(time.perf_counter() - s)
    return min(t), lu.L.nnz + lu.U.nnz


for n in [int(a) for a in sys.argv[1:]] or [10, 40]:
    h = 1 / 60
    k = 0.01 * (0.5 / h) ** 2
    net = P.Net(n, k=k)
    rng = np.random.default_rng(1)
    x = net.x0 * 1.05
    x[:, 2] = 0.01 * rng.standard_normal(net.N)
    K = net.K(x)
    M = net.Msp
    lam = np.linalg.eigvals(P.A2)[0]
    res = {}
    res["primal midpoint 3N real"] = best(M + 0.25 * h * h * K)
    res["primal EPC full 6N real"] = best(sp.bmat([[M + h * h * P.A2[0, 0] * K, h * h * P.A2[0, 1] * K],
                                                  [h * h * P.A2[1, 0] * K, M + h * h * P.A2[1, 1] * K]]))
    res["primal EPC 3N complex"] = best((M + h * h * lam * K).astype(complex))
    res["primal EPC 3N real shift"] = best(M + h * h * (1 / 6) * K)
    d, L = net.span(x)
    e = d / L[:, None]
    E = net.E
    rows = np.repeat(np.arange(E), 6)
    cols = np.c_[3 * net.b[:, None] + np.arange(3), 3 * net.a[:, None] + np.arange(3)].ravel()
    vals = np.c_[e, -e].ravel()
    J = sp.csr_matrix((vals, (rows, cols)), shape=(E, 3 * net.N))
    S = (J @ J.T) / net.m
    G = sp.identity(E) * (1 / (h * h * k * 0.25))
    res["dual midpoint E real"] = best(S + G)
    Ai = np.linalg.inv(P.A2) / (h * h * k)
    res["dual EPC 2E real"] = best(sp.bmat([[S + Ai[0, 0] * sp.identity(E), Ai[0, 1] * sp.identity(E)],
                                            [Ai[1, 0] * sp.identity(E), S + Ai[1, 1] * sp.identity(E)]]))
    res["dual EPC E complex"] = best((S + sp.identity(E) / (h * h * k * lam)).astype(complex))
    base_p = res["primal midpoint 3N real"][0]
    base_d = res["dual midpoint E real"][0]
    print(f"net {n} x {n}: N = {net.N}, threads = {E}")
    for key, (t, nnz) in res.items():
        base = base_p if key.startswith("primal") else base_d
        print(f"  {key:28s} {1e3 * t:8.3f} ms  nnz(L+U) {nnz:8d}  x{t / base:.2f}")
