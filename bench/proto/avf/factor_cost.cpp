// (c) factor cost with Eigen, the engine's library: the 40 x 40 net's thread-row (dual) matrix
// S + Gamma (SPD: SimplicialLDLT, AMD, what the spring block factors) against the two-stage
// collocation's 2E system (2x2 coupled by A^-2, unsymmetric: SparseLU) and its one complex
// E system (SparseLU<complex>), and the primal node-space 3N / 6N versions. Every thread taut,
// stretched 5 %, rippled out of plane; h = 1/60, omega_e h = 0.5. Best of 7, numeric factor
// only (pattern analysed once, as the engine does while the pattern holds).
// Build: g++ -O2 -DNDEBUG -I/usr/include/eigen3 factor_cost.cpp -o factor_cost
#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <chrono>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using SpD = Eigen::SparseMatrix<double>;
using SpC = Eigen::SparseMatrix<std::complex<double>>;
using T = Eigen::Triplet<double>;

template <class F>
double best(F f, int reps = 7) {
    double b = 1e9;
    for (int r = 0; r < reps; ++r) {
        auto s = std::chrono::steady_clock::now();
        f();
        b = std::min(b,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - s).count());
    }
    return b;
}

int main(int argc, char** argv) {
    const int n = argc > 1 ? std::atoi(argv[1]) : 40;
    const double h = 1.0 / 60, m = 0.01, wh = 0.5, k = m * (wh / h) * (wh / h), L0 = 0.05;
    const int N = n * n;
    std::vector<Eigen::Vector3d> x(N);
    std::mt19937 rng(1);
    std::normal_distribution<double> g(0, 0.01);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            x[i * n + j] = Eigen::Vector3d(1.05 * L0 * i, 1.05 * L0 * j, g(rng));
    std::vector<std::pair<int, int>> th;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            if (j + 1 < n)
                th.push_back({i * n + j, i * n + j + 1});
            if (i + 1 < n)
                th.push_back({i * n + j, (i + 1) * n + j});
        }
    const int E = static_cast<int>(th.size());
    // Lambda of A^2 (2-stage Gauss): 1/24 +- i sqrt(3)/24; A^-2 entries.
    const double s3 = std::sqrt(3.0);
    Eigen::Matrix2d A;
    A << 0.25, 0.25 - s3 / 6, 0.25 + s3 / 6, 0.25;
    const Eigen::Matrix2d A2 = A * A, Ai = A2.inverse() / (h * h * k);
    const std::complex<double> lam(1.0 / 24, s3 / 24);
    // Primal K blocks.
    std::vector<T> kt, mt;
    std::vector<Eigen::Vector3d> e(E);
    for (int t = 0; t < E; ++t) {
        auto [a, b] = th[t];
        Eigen::Vector3d d = x[b] - x[a];
        double L = d.norm();
        e[t] = d / L;
        Eigen::Matrix3d ee = e[t] * e[t].transpose();
        Eigen::Matrix3d Kb = k * (ee + (1 - L0 / L) * (Eigen::Matrix3d::Identity() - ee));
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                kt.emplace_back(3 * a + r, 3 * a + c, Kb(r, c));
                kt.emplace_back(3 * b + r, 3 * b + c, Kb(r, c));
                kt.emplace_back(3 * a + r, 3 * b + c, -Kb(r, c));
                kt.emplace_back(3 * b + r, 3 * a + c, -Kb(r, c));
            }
    }
    SpD K(3 * N, 3 * N), M(3 * N, 3 * N);
    K.setFromTriplets(kt.begin(), kt.end());
    for (int i = 0; i < 3 * N; ++i)
        mt.emplace_back(i, i, m);
    M.setFromTriplets(mt.begin(), mt.end());
    // Dual S = J M^-1 J'.
    std::vector<T> jt;
    for (int t = 0; t < E; ++t)
        for (int r = 0; r < 3; ++r) {
            jt.emplace_back(t, 3 * th[t].second + r, e[t](r));
            jt.emplace_back(t, 3 * th[t].first + r, -e[t](r));
        }
    SpD J(E, 3 * N);
    J.setFromTriplets(jt.begin(), jt.end());
    SpD S = SpD(J * J.transpose()) / m;
    SpD IE(E, E);
    IE.setIdentity();
    auto stack2 = [](const SpD& a00, const SpD& a01, const SpD& a10, const SpD& a11) {
        const int n0 = a00.rows();
        std::vector<T> t;
        auto put = [&](const SpD& s, int ro, int co) {
            for (int c = 0; c < s.outerSize(); ++c)
                for (SpD::InnerIterator it(s, c); it; ++it)
                    t.emplace_back(it.row() + ro, it.col() + co, it.value());
        };
        put(a00, 0, 0);
        put(a01, 0, n0);
        put(a10, n0, 0);
        put(a11, n0, n0);
        SpD out(2 * n0, 2 * n0);
        out.setFromTriplets(t.begin(), t.end());
        return out;
    };
    const SpD dualMid = S + IE * (1 / (h * h * k * 0.25));
    const SpD dual2 = stack2(S + Ai(0, 0) * IE, Ai(0, 1) * IE, Ai(1, 0) * IE, S + Ai(1, 1) * IE);
    SpC dualC = S.cast<std::complex<double>>() +
                IE.cast<std::complex<double>>() * (1.0 / (h * h * k * lam));
    const SpD primMid = M + (0.25 * h * h) * K;
    const SpD prim2 = stack2(M + h * h * A2(0, 0) * K, h * h * A2(0, 1) * K, h * h * A2(1, 0) * K,
                             M + h * h * A2(1, 1) * K);
    SpC primC = M.cast<std::complex<double>>() + (h * h * lam) * K.cast<std::complex<double>>();

    Eigen::SimplicialLDLT<SpD, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt;
    Eigen::SparseLU<SpD, Eigen::COLAMDOrdering<int>> lu;
    Eigen::SparseLU<SpC, Eigen::COLAMDOrdering<int>> luc;
    std::printf("net %d x %d: N %d, threads %d (Eigen, numeric factor, best of 7, ms)\n", n, n, N,
                E);
    auto report = [](const char* what, double t, double base) {
        std::printf("  %-44s %9.3f ms  x%.2f\n", what, 1e3 * t, t / base);
    };
    // One system's four factorisations, timed against its LDLT: the midpoint (today's kind), the
    // same matrix by LU, the two-stage system, the complex shift.
    auto compare = [&](const char* kind, const SpD& mid, const SpD& two, const SpC& shifted) {
        ldlt.analyzePattern(mid);
        const double base = best([&] { ldlt.factorize(mid); });
        const std::string name(kind);
        report((name + " midpoint, LDLT (today's kind)").c_str(), base, base);
        lu.analyzePattern(mid);
        report((name + " midpoint, SparseLU").c_str(), best([&] { lu.factorize(mid); }), base);
        lu.analyzePattern(two);
        report((name + " two-stage, SparseLU").c_str(), best([&] { lu.factorize(two); }), base);
        luc.analyzePattern(shifted);
        report((name + " complex shift, SparseLU<complex>").c_str(),
               best([&] { luc.factorize(shifted); }), base);
        return base;
    };
    const double tdl = compare("dual E", dualMid, dual2, dualC);
    // Complex arithmetic in the same LDLT (a Hermitian matrix of the same pattern: the flops of
    // an LDL' of the complex-symmetric shifted system, which needs no pivoting either).
    {
        Eigen::SimplicialLDLT<SpC, Eigen::Lower, Eigen::AMDOrdering<int>> cl;
        SpC herm = dualMid.cast<std::complex<double>>();
        cl.analyzePattern(herm);
        report("dual E complex, LDLT-kind (complex flops)", best([&] { cl.factorize(herm); }), tdl);
    }
    compare("primal 3N", primMid, prim2, primC);
    // Back-solve cost, for the iteration counts.
    ldlt.analyzePattern(dualMid);
    ldlt.factorize(dualMid);
    Eigen::VectorXd rhs = Eigen::VectorXd::Ones(E), sol;
    const double tbs = best([&] { sol = ldlt.solve(rhs); }, 21);
    std::printf("  dual E LDLT back-solve %.3f ms (%.3f of its factor)\n", 1e3 * tbs, tbs / tdl);
    return 0;
}
