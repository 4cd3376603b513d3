"""Issue 22 prototype: 2-stage energy-preserving collocation (Hairer 2010, 'AVF collocation',
order 4) against Fox-Goodwin (Newmark beta = 1/12) and the midpoint discrete gradient (Gonzalez)
on a standalone lumped-mass net of tension-only threads. Not engine code.

Net: n x n nodes of mass m, mesh L0, threads k max(L - L0, 0) between grid neighbours.
Uniform gravity drops out of every scheme's relative motion exactly (all three are affine in a
constant force), so it is left out: the internal energy is the same with or without it.

EPC step (s = 2, Gauss nodes c, Butcher A, b): u(sigma) the quadratic through x0, X1, X2 at
0, c1, c2; Fbar_k = int_0^1 l_k(sigma) / b_k F(u(sigma)) dsigma (l_k linear Lagrange on c);
    X_j = x0 + h c_j v0 + h^2 sum_k (A^2)_jk M^-1 Fbar_k,
    v1 = v0 + h sum_k b_k M^-1 Fbar_k,   x1 = x0 + h v0 + h^2 sum_k (b A)_k M^-1 Fbar_k.
Energy is exact when the integrals are: each thread's integral is split at its kinks (roots of
|d(sigma)|^2 = L0^2, a quartic) and done by Gauss-Legendre on each piece.
"""
import time
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

S3 = np.sqrt(3.0)
GC = np.array([0.5 - S3 / 6, 0.5 + S3 / 6])
GB = np.array([0.5, 0.5])
GA = np.array([[0.25, 0.25 - S3 / 6], [0.25 + S3 / 6, 0.25]])
A2 = GA @ GA
BA = GB @ GA
NQ = 6
XI, WQ = np.polynomial.legendre.leggauss(NQ)


def lagr_coeffs(nodes):
    """Coefficients (power basis, low first) of the Lagrange polynomials on nodes."""
    out = []
    for i in range(len(nodes)):
        p = np.array([1.0])
        for j, nj in enumerate(nodes):
            if j != i:
                p = np.polynomial.polynomial.polymul(p, np.array([-nj, 1.0]) / (nodes[i] - nj))
        out.append(np.pad(p, (0, len(nodes) - len(p))))
    return np.array(out)


LT = lagr_coeffs(np.array([0.0, GC[0], GC[1]]))  # (3 basis, 3 coeffs): x(sigma)
LK = lagr_coeffs(GC)  # (2, 2): l_k


class Net:
    def __init__(self, n, mesh=0.05, mass=0.01, k=400.0, spread=0.5, lift=0.0):
        self.n, self.m, self.k, self.L0 = n, mass, k, mesh
        N = n * n
        ij = np.array([(i, j) for i in range(n) for j in range(n)], float)
        off = mesh * np.c_[ij[:, 0] - 0.5 * (n - 1), ij[:, 1] - 0.5 * (n - 1), np.zeros(N)]
        corner = 0.5 * mesh * np.hypot(n - 1, n - 1)
        self.x0 = off.copy()
        self.v0 = spread / corner * off
        if lift:
            for c, s in zip([0, n - 1, (n - 1) * n, n * n - 1], [1, -1, -1, 1]):
                self.v0[c, 2] += s * lift
        a, b = [], []
        for i in range(n):
            for j in range(n):
                if j + 1 < n:
                    a.append(i * n + j); b.append(i * n + j + 1)
                if i + 1 < n:
                    a.append(i * n + j); b.append((i + 1) * n + j)
        self.a, self.b = np.array(a), np.array(b)
        self.N, self.E = N, len(a)
        # COO pattern of per-thread 3x3 blocks: (a,a) +, (b,b) +, (a,b) -, (b,a) -
        r, cc = [], []
        for (p, q) in [(self.a, self.a), (self.b, self.b), (self.a, self.b), (self.b, self.a)]:
            r.append((3 * p[:, None, None] + np.arange(3)[None, :, None]).repeat(3, 2))
            cc.append((3 * q[:, None, None] + np.arange(3)[None, None, :]).repeat(3, 1))
        self.rows, self.cols = np.concatenate([x.ravel() for x in r]), np.concatenate([x.ravel() for x in cc])
        self.Msp = sp.identity(3 * N, format="csc") * mass

    # ---- basics
    def span(self, x):
        d = x[self.b] - x[self.a]
        return d, np.linalg.norm(d, axis=1)

    def potential(self, x):
        _, L = self.span(x)
        c = np.maximum(L - self.L0, 0)
        return 0.5 * self.k * np.sum(c * c)

    def scatter(self, fe):
        """fe: force on a (pull towards b) per thread -> node forces."""
        F = np.zeros((self.N, 3))
        np.add.at(F, self.a, fe)
        np.add.at(F, self.b, -fe)
        return F

    def force(self, x):
        d, L = self.span(x)
        T = self.k * np.maximum(L - self.L0, 0)
        return self.scatter((T / L)[:, None] * d)

    def kblocks(self, d, L):
        """Hessian blocks of a thread's V wrt its span d (taut: axial + geometric; slack 0)."""
        e = d / L[..., None]
        ee = e[..., :, None] * e[..., None, :]
        taut = (L > self.L0).astype(float)
        g = np.maximum(1 - self.L0 / L, 0)
        I = np.eye(3)
        return self.k * taut[..., None, None] * (ee + g[..., None, None] * (I - ee))

    def assemble(self, blocks):
        """blocks (E,3,3) of d(gradient on b)/d(x_b) -> sparse 3N x 3N."""
        vals = np.concatenate([blocks.ravel(), blocks.ravel(), -blocks.ravel(), -blocks.ravel()])
        return sp.csc_matrix((vals, (self.rows, self.cols)), shape=(3 * self.N, 3 * self.N))

    def K(self, x):
        d, L = self.span(x)
        return self.assemble(self.kblocks(d, L))

    def energy(self, x, v):
        vm = v - v.mean(0)
        return 0.5 * self.m * np.sum(vm * vm) + self.potential(x)


STATS = {}


def stat(key, val=1):
    STATS[key] = STATS.get(key, 0) + val


def timed_lu(A, key):
    t = time.perf_counter()
    lu = spla.splu(A.tocsc())
    stat(key + "_t", time.perf_counter() - t)
    stat(key)
    return lu


TOL = 1e-12  # Newton: max position update (m)


# ---------------- Fox-Goodwin (Newmark beta = 1/12, gamma = 1/2), full Newton
class FoxGoodwin:
    name = "fox-goodwin"

    def __init__(self, net, h, beta=1.0 / 12):
        self.net, self.h, self.beta = net, h, beta

    def start(self, x, v):
        self.acc = self.net.force(x) / self.net.m
        return x.copy(), v.copy()

    def step(self, x, v):
        net, h, be = self.net, self.h, self.beta
        pred = x + h * v + h * h * (0.5 - be) * self.acc
        x1 = pred + h * h * be * self.acc
        for it in range(50):
            R = net.m * (x1 - pred) - h * h * be * net.force(x1)
            J = net.Msp + h * h * be * net.K(x1)
            dx = timed_lu(J, "fg_lu").solve(-R.ravel()).reshape(-1, 3)
            x1 += dx
            stat("fg_newton")
            if np.abs(dx).max() < TOL:
                break
        a1 = net.force(x1) / net.m
        v1 = v + 0.5 * h * (self.acc + a1)
        self.acc = a1
        return x1, v1


# ---------------- midpoint discrete gradient (Gonzalez), full Newton (unsymmetric Jacobian)
def dg_D(k, c0, c1):
    """D = (V(c1) - V(c0)) / (c1 - c0) and dD/dc1, V = k/2 max(c, 0)^2, piecewise exact."""
    D = np.zeros_like(c0); Dp = np.zeros_like(c0)
    tt = (c0 > 0) & (c1 > 0)
    D[tt] = 0.5 * k * (c0[tt] + c1[tt]); Dp[tt] = 0.5 * k
    cg = (c0 <= 0) & (c1 > 0)
    q = c1[cg] - c0[cg]
    D[cg] = 0.5 * k * c1[cg] ** 2 / q; Dp[cg] = 0.5 * k * c1[cg] * (c1[cg] - 2 * c0[cg]) / q ** 2
    rl = (c0 > 0) & (c1 <= 0)
    q = c0[rl] - c1[rl]
    D[rl] = 0.5 * k * c0[rl] ** 2 / q; Dp[rl] = 0.5 * k * c0[rl] ** 2 / q ** 2
    return D, Dp


class MidpointDG:
    name = "midpoint-dg"

    def __init__(self, net, h):
        self.net, self.h = net, h

    def start(self, x, v):
        return x.copy(), v.copy()

    def step(self, x, u):
        net, h = self.net, self.h
        d0, L0 = net.span(x)
        c0 = L0 - net.L0
        x1 = x + h * u
        for it in range(50):
            d1, L1 = net.span(x1)
            c1 = L1 - net.L0
            D, Dp = dg_D(net.k, c0, c1)
            S = L0 + L1
            mvec = (d0 + d1) / S[:, None]
            grad_b = D[:, None] * mvec  # dV/dx_b
            R = net.m * (x1 - x - h * u) + 0.5 * h * h * net.scatter(-grad_b)
            e1 = d1 / L1[:, None]
            me = mvec[:, :, None] * e1[:, None, :]
            blocks = Dp[:, None, None] * me + (D / S)[:, None, None] * (np.eye(3) - me)
            J = net.Msp + 0.5 * h * h * net.assemble(blocks)
            dx = timed_lu(J, "dg_lu").solve(-R.ravel()).reshape(-1, 3)
            x1 += dx
            stat("dg_newton")
            if np.abs(dx).max() < TOL:
                break
        u1 = 2 * (x1 - x) / h - u
        return x1, u1


# ---------------- 2-stage energy-preserving collocation
def kink_breaks(p0, p1, p2, L0, nsamp=33):
    """Roots in (0,1) of |p0 + p1 s + p2 s^2|^2 - L0^2 per thread, padded with 1: (E,4)."""
    q = np.stack([np.einsum("ij,ij->i", p0, p0) - L0 ** 2, 2 * np.einsum("ij,ij->i", p0, p1),
                  np.einsum("ij,ij->i", p1, p1) + 2 * np.einsum("ij,ij->i", p0, p2),
                  2 * np.einsum("ij,ij->i", p1, p2), np.einsum("ij,ij->i", p2, p2)], 1)
    s = np.linspace(0, 1, nsamp)
    f = np.polynomial.polynomial.polyval(s, q.T)  # (E, nsamp)
    ch = np.sign(f[:, :-1]) * np.sign(f[:, 1:]) < 0
    out = np.ones((len(p0), 4))
    ei, si = np.nonzero(ch)
    if len(ei):
        lo, hi = s[si].copy(), s[si + 1].copy()
        qq = q[ei]
        flo = np.polynomial.polynomial.polyval(lo, qq.T, tensor=False)
        for _ in range(55):
            mid = 0.5 * (lo + hi)
            fm = np.polynomial.polynomial.polyval(mid, qq.T, tensor=False)
            same = np.sign(fm) == np.sign(flo)
            lo = np.where(same, mid, lo); flo = np.where(same, fm, flo)
            hi = np.where(same, hi, mid)
        r = 0.5 * (lo + hi)
        # slot per root within its thread
        order = np.lexsort((r, ei))
        ei, r = ei[order], r[order]
        first = np.r_[True, ei[1:] != ei[:-1]]
        idx = np.arange(len(ei)) - np.maximum.accumulate(np.where(first, np.arange(len(ei)), 0))
        keep = idx < 4
        out[ei[keep], idx[keep]] = r[keep]
        stat("kinks", len(ei))
    return np.sort(out, 1)


class EPC:
    """mode: 'full' (Newton, exact stage Jacobian, 6N LU each iteration),
    'simp' (simplified Newton: K at the step start, exact 2x2 coupling, one 6N LU a step),
    'shift' (one real 3N factor M + h^2 gamma K(x0), block-diagonal, stationary iteration),
    'gmres' (the same real factor as GMRES preconditioner on the full-Newton linear systems),
    'tri' (the same one real 3N factor, block Gauss-Seidel over the stages: the preconditioner
    I x M + h^2 [[gamma, 0], [ell, gamma]] x K, two back-solves and one K product an iteration;
    gamma = 0.045, ell = 0.27 put its linear rate at 0.002 for mu = (omega h)^2 <= 1, 0.018 to
    2.9, 0.11 at mu -> inf, against the block-diagonal shift's 0.07, 0.18, 0.87).
    kat: where K is frozen, 'x0' (step start) or 'mid' (the predictor at h/2)."""

    def __init__(self, net, h, mode="full", gamma=None, ell=0.27, kat="x0", linesearch=False):
        self.net, self.h, self.mode, self.linesearch = net, h, mode, linesearch
        self.ell, self.kat = ell, kat
        lam = np.linalg.eigvals(A2)
        self.gamma = gamma if gamma is not None else (
            0.045 if mode == "tri" else abs(lam[0]) ** 2 / lam[0].real)
        self.name = "epc-" + mode

    def start(self, x, v):
        return x.copy(), v.copy()

    def quad(self, x0, X, want_jac):
        net = self.net
        xs = [x0, X[0], X[1]]
        ds = [xx[net.b] - xx[net.a] for xx in xs]
        p = [sum(LT[j, i] * ds[j] for j in range(3)) for i in range(3)]  # d(s) = p0 + p1 s + p2 s^2
        br = kink_breaks(p[0], p[1], p[2], net.L0)
        bk = np.concatenate([np.zeros((net.E, 1)), br, np.ones((net.E, 1))], 1)  # (E,6)
        lo, hi = bk[:, :-1], bk[:, 1:]
        sig = (lo[:, :, None] + (hi - lo)[:, :, None] * 0.5 * (XI + 1)).reshape(net.E, -1)
        w = ((hi - lo)[:, :, None] * 0.5 * WQ).reshape(net.E, -1)
        d = p[0][:, None, :] + p[1][:, None, :] * sig[..., None] + p[2][:, None, :] * sig[..., None] ** 2
        L = np.linalg.norm(d, axis=2)
        T = net.k * np.maximum(L - net.L0, 0)
        f = (T / L)[..., None] * d  # force on a
        lk = [np.polynomial.polynomial.polyval(sig, LK[kk]) / GB[kk] for kk in range(2)]
        Fbar = [net.scatter(np.einsum("eq,eqi->ei", w * lk[kk], f)) for kk in range(2)]
        if not want_jac:
            return Fbar, None
        Kq = net.kblocks(d, L)  # (E,Q,3,3)
        lt = [np.polynomial.polynomial.polyval(sig, LT[j]) for j in (1, 2)]
        Kb = [[net.assemble(np.einsum("eq,eqij->eij", w * lk[kk] * lt[j], Kq)) for j in range(2)]
              for kk in range(2)]
        return Fbar, Kb

    def residual(self, x0, v0, X, Fbar):
        h, m = self.h, self.net.m
        return [m * (X[j] - x0 - h * GC[j] * v0) - h * h * (A2[j, 0] * Fbar[0] + A2[j, 1] * Fbar[1])
                for j in range(2)]

    def step(self, x0, v0):
        net, h = self.net, self.h
        # predictor: constant-acceleration
        a0 = net.force(x0) / net.m
        X = [x0 + h * GC[j] * v0 + 0.5 * (h * GC[j]) ** 2 * a0 for j in range(2)]
        n3 = 3 * net.N
        if self.mode in ("simp", "shift", "gmres", "tri"):
            K0 = net.K(x0 if self.kat == "x0" else x0 + 0.5 * h * v0 + 0.125 * h * h * a0)
            if self.mode == "simp":
                J = sp.bmat([[net.Msp + h * h * A2[0, 0] * K0, h * h * A2[0, 1] * K0],
                             [h * h * A2[1, 0] * K0, net.Msp + h * h * A2[1, 1] * K0]])
                lu = timed_lu(J, "epc_lu6")
            else:
                lu = timed_lu(net.Msp + h * h * self.gamma * K0, "epc_lu3")
        for it in range(200):
            want = self.mode in ("full", "gmres")
            Fbar, Kb = self.quad(x0, X, want)
            stat("epc_quad")
            R = self.residual(x0, v0, X, Fbar)
            if want:
                J = sp.bmat([[net.Msp + h * h * (A2[0, 0] * Kb[0][0] + A2[0, 1] * Kb[1][0]),
                              h * h * (A2[0, 0] * Kb[0][1] + A2[0, 1] * Kb[1][1])],
                             [h * h * (A2[1, 0] * Kb[0][0] + A2[1, 1] * Kb[1][0]),
                              net.Msp + h * h * (A2[1, 0] * Kb[0][1] + A2[1, 1] * Kb[1][1])]]).tocsc()
            rhs = -np.concatenate([R[0].ravel(), R[1].ravel()])
            if self.mode == "full":
                dx = timed_lu(J, "epc_lu6").solve(rhs)
            elif self.mode == "simp":
                dx = lu.solve(rhs); stat("epc_bsolve6")
            elif self.mode == "tri":
                d1 = lu.solve(rhs[:n3])
                d2 = lu.solve(rhs[n3:] - h * h * self.ell * (K0 @ d1))
                dx = np.concatenate([d1, d2]); stat("epc_bsolve3", 2)
            elif self.mode == "shift":
                dx = np.concatenate([lu.solve(rhs[:n3]), lu.solve(rhs[n3:])]); stat("epc_bsolve3", 2)
            else:
                Mop = spla.LinearOperator((2 * n3, 2 * n3), matvec=lambda r: np.concatenate(
                    [lu.solve(r[:n3]), lu.solve(r[n3:])]))
                cnt = [0]
                def cb(_):
                    cnt[0] += 1
                dx, info = spla.gmres(J, rhs, M=Mop, tol=1e-10, atol=1e-16, restart=30, maxiter=5,
                                      callback=cb, callback_type="pr_norm")
                stat("epc_bsolve3", 2 * (cnt[0] + 1))
            if self.linesearch:
                # backtracking on |R| (halving, up to 12 cuts): the kinks make plain Newton cycle
                r0 = np.linalg.norm(rhs)
                t = 1.0
                for _ in range(12):
                    Xt = [X[0] + t * dx[:n3].reshape(-1, 3), X[1] + t * dx[n3:].reshape(-1, 3)]
                    Ft, _ = self.quad(x0, Xt, False)
                    Rt = self.residual(x0, v0, Xt, Ft)
                    if np.linalg.norm(np.concatenate([Rt[0].ravel(), Rt[1].ravel()])) < (1 - 1e-4 * t) * r0:
                        break
                    t *= 0.5
                    stat("epc_cuts")
                dx = t * dx
            X = [X[0] + dx[:n3].reshape(-1, 3), X[1] + dx[n3:].reshape(-1, 3)]
            stat("epc_newton")
            if np.abs(dx).max() < TOL:
                break
        else:
            stat("epc_noconv")
        Fbar, _ = self.quad(x0, X, False)
        acc = [Fb / net.m for Fb in Fbar]
        v1 = v0 + h * (GB[0] * acc[0] + GB[1] * acc[1])
        x1 = x0 + h * v0 + h * h * (BA[0] * acc[0] + BA[1] * acc[1])
        return x1, v1


# ---------------- reference: velocity Verlet
def verlet(net, h, T, sample):
    x, v = net.x0.copy(), net.v0.copy()
    a = net.force(x) / net.m
    steps = int(round(T / h)); every = int(round(sample / h))
    out = []
    for i in range(1, steps + 1):
        v += 0.5 * h * a
        x += h * v
        a = net.force(x) / net.m
        v += 0.5 * h * a
        if i % every == 0:
            out.append(x.copy())
    return np.array(out)


def run(scheme, T, sample=None, energy=False):
    net = scheme.net
    x, v = scheme.start(net.x0, net.v0)
    steps = int(round(T / scheme.h))
    every = int(round(sample / scheme.h)) if sample else 0
    E0 = net.energy(x, v); lo = hi = 1.0
    out = []
    for i in range(1, steps + 1):
        x, v = scheme.step(x, v)
        if energy:
            r = net.energy(x, v) / E0
            if not np.isfinite(r):
                lo, hi = np.nan, np.nan; break
            lo, hi = min(lo, r), max(hi, r)
        if every and i % every == 0:
            out.append(x.copy())
    return np.array(out), lo, hi
