// SPDX-License-Identifier: MIT
// Linear stability of circular Couette flow against axisymmetric Taylor vortices.
//
// With v_theta = A r + B / r, Omega = v_theta / r, lengths in d and times in d^2 / nu, a
// perturbation (u, v, w) exp(sigma t + i k z) obeys (Chandrasekhar, Hydrodynamic and
// Hydromagnetic Stability, ch. VII)
//     (L - sigma) L u = 2 k^2 Omega v,    (L - sigma) v = 2 A u,
//     L = D D* - k^2,  D = d/dr,  D* = d/dr + 1/r,   u = D u = v = 0 on both walls.
// Eliminating v, u = M(sigma) u with M = [(L - sigma) L]^-1 2 k^2 Omega (L - sigma)^-1 2 A.
// M scales as Re^2, and its largest eigenvalue falls as sigma grows, so a growth rate is where
// Re^2 mu(sigma) = 1 (found by bisection) and the marginal Reynolds number is mu(0)^(-1/2).
// mu comes from power iteration: M is smoothing (an inverse of a fourth-order operator), its
// leading eigenvalue is well separated, and this needs no general eigenvalue solver.
#include "emergent/kit/couette_stability.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace emergent {

namespace {

constexpr double kPi = 3.141592653589793;

using Matrix = std::vector<double>;  // n x n, row-major

/// LU factorisation with partial pivoting, then solves; n is small (~33).
class LuSolver {
public:
    LuSolver(Matrix a, int n) : a_(std::move(a)), pivot_(n), n_(n) {
        for (int c = 0; c < n; ++c) {
            int p = c;
            for (int r = c + 1; r < n; ++r)
                if (std::fabs(a_[r * n + c]) > std::fabs(a_[p * n + c])) p = r;
            if (a_[p * n + c] == 0) throw std::runtime_error("CouetteStability: singular operator");
            pivot_[c] = p;
            if (p != c)
                for (int k = 0; k < n; ++k) std::swap(a_[c * n + k], a_[p * n + k]);
            for (int r = c + 1; r < n; ++r) {
                const double f = a_[r * n + c] /= a_[c * n + c];
                for (int k = c + 1; k < n; ++k) a_[r * n + k] -= f * a_[c * n + k];
            }
        }
    }
    std::vector<double> solve(std::vector<double> b) const {
        const int n = n_;
        // The factorisation swapped whole rows, multipliers included: all swaps come first.
        for (int c = 0; c < n; ++c) std::swap(b[c], b[pivot_[c]]);
        for (int c = 0; c < n; ++c)
            for (int r = c + 1; r < n; ++r) b[r] -= a_[r * n + c] * b[c];
        for (int r = n - 1; r >= 0; --r) {
            for (int k = r + 1; k < n; ++k) b[r] -= a_[r * n + k] * b[k];
            b[r] /= a_[r * n + r];
        }
        return b;
    }

private:
    Matrix a_;
    std::vector<int> pivot_;
    int n_;
};

Matrix multiply(const Matrix& a, const Matrix& b, int n) {
    Matrix c(n * n, 0.0);
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const double aik = a[i * n + k];
            for (int j = 0; j < n; ++j) c[i * n + j] += aik * b[k * n + j];
        }
    return c;
}

/// The gap on a Chebyshev grid: points r_j from r_o (j = 0) to r_i (j = n - 1), d/dr there.
struct GapGrid {
    std::vector<double> r;
    Matrix d;  // d/dr
};

GapGrid gap_grid(double r_i, double r_o, int n) {
    const int order = n - 1;
    GapGrid g;
    std::vector<double> x(n), c(n);
    for (int j = 0; j < n; ++j) {
        x[j] = std::cos(kPi * j / order);
        c[j] = (j == 0 || j == order ? 2.0 : 1.0) * (j % 2 ? -1.0 : 1.0);
        g.r.push_back(0.5 * (r_i + r_o) + 0.5 * (r_o - r_i) * x[j]);
    }
    g.d.assign(n * n, 0.0);
    const double scale = 2.0 / (r_o - r_i);
    for (int i = 0; i < n; ++i) {
        double diagonal = 0;
        for (int j = 0; j < n; ++j) {
            if (i == j) continue;
            const double v = c[i] / c[j] / (x[i] - x[j]);
            g.d[i * n + j] = scale * v;
            diagonal -= scale * v;
        }
        g.d[i * n + i] = diagonal;  // exact row sums of zero: derivatives of constants vanish
    }
    return g;
}

}  // namespace

CouetteStability::CouetteStability(double radius_ratio, int points) : eta_(radius_ratio), n_(points) {
    if (!(radius_ratio > 0 && radius_ratio < 1))
        throw std::invalid_argument("CouetteStability: radius ratio " + std::to_string(radius_ratio) +
                                    " is not in (0, 1)");
    if (points < 8) throw std::invalid_argument("CouetteStability: fewer than 8 points across the gap");
    GapGrid g = gap_grid(eta_ / (1 - eta_), 1 / (1 - eta_), n_);
    r_ = std::move(g.r);
    ddr_ = std::move(g.d);
}

double CouetteStability::coupling_eigenvalue(double sigma, double k) const {
    const int n = n_;
    const double r_i = eta_ / (1 - eta_), r_o = 1 / (1 - eta_);
    // Base flow at Re = 1: Omega_i = 1 / r_i (in units nu / d^2), outer wall at rest.
    const double omega_i = 1 / r_i;
    const double a = -omega_i * r_i * r_i / (r_o * r_o - r_i * r_i);
    const double b = omega_i * r_i * r_i * r_o * r_o / (r_o * r_o - r_i * r_i);

    Matrix dstar = ddr_;  // D* = D + 1/r
    for (int i = 0; i < n; ++i) dstar[i * n + i] += 1 / r_[i];
    Matrix l = multiply(ddr_, dstar, n);
    for (int i = 0; i < n; ++i) l[i * n + i] -= k * k;
    Matrix shifted = l;  // L - sigma
    for (int i = 0; i < n; ++i) shifted[i * n + i] -= sigma;
    Matrix fourth = multiply(shifted, l, n);  // (L - sigma) L

    // Boundary rows: v = 0 and u = 0 at both walls (rows 0, n-1), D u = 0 (rows 1, n-2).
    auto set_row = [n](Matrix& m, int row, const double* values) {
        std::copy(values, values + n, m.begin() + row * n);
    };
    std::vector<double> unit(n, 0.0);
    for (int w : {0, n - 1}) {
        std::fill(unit.begin(), unit.end(), 0.0);
        unit[w] = 1;
        set_row(shifted, w, unit.data());
        set_row(fourth, w, unit.data());
    }
    set_row(fourth, 1, &ddr_[0]);
    set_row(fourth, n - 2, &ddr_[(n - 1) * n]);
    const LuSolver solve_v(std::move(shifted), n), solve_u(std::move(fourth), n);

    auto apply = [&](const std::vector<double>& u) {
        std::vector<double> rhs(n);
        for (int i = 0; i < n; ++i) rhs[i] = 2 * a * u[i];
        rhs[0] = rhs[n - 1] = 0;
        const std::vector<double> v = solve_v.solve(rhs);
        for (int i = 0; i < n; ++i) rhs[i] = 2 * k * k * (a + b / (r_[i] * r_[i])) * v[i];
        rhs[0] = rhs[1] = rhs[n - 2] = rhs[n - 1] = 0;
        return solve_u.solve(rhs);
    };

    // Power iteration from a profile that already meets the boundary conditions.
    std::vector<double> u(n);
    for (int i = 0; i < n; ++i) {
        const double x = (2 * r_[i] - r_i - r_o) / (r_o - r_i);
        u[i] = (1 - x * x) * (1 - x * x);
    }
    double mu = 0;
    for (int it = 0; it < 2000; ++it) {
        std::vector<double> next = apply(u);
        double uu = 0, un = 0, nn = 0;
        for (int i = 0; i < n; ++i) uu += u[i] * u[i], un += u[i] * next[i], nn += next[i] * next[i];
        const double estimate = un / uu;
        const double norm = std::sqrt(nn);
        if (!(norm > 0)) return 0;
        for (int i = 0; i < n; ++i) u[i] = next[i] / norm;
        if (it > 2 && std::fabs(estimate - mu) <= 1e-12 * std::fabs(estimate)) return estimate;
        mu = estimate;
    }
    return mu;
}

double CouetteStability::marginal_reynolds(double k) const {
    const double mu = coupling_eigenvalue(0, k);
    return mu > 0 ? 1 / std::sqrt(mu) : INFINITY;
}

double CouetteStability::growth_rate(double reynolds, double k) const {
    const double re2 = reynolds * reynolds;
    auto excess = [&](double sigma) { return re2 * coupling_eigenvalue(sigma, k) - 1; };
    // Below -(k^2 + 9) L - sigma comes close to singular (L's largest eigenvalue is about
    // -(k^2 + pi^2)); modes that decay that fast do not matter here.
    double lo = -(k * k + 9);
    if (excess(lo) <= 0) return lo;
    double hi = 1;
    while (excess(hi) > 0) {
        lo = hi;
        hi *= 2;
    }
    while (hi - lo > 1e-10 * (1 + std::fabs(hi))) {
        const double mid = 0.5 * (lo + hi);
        (excess(mid) > 0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

CouetteStability::Onset CouetteStability::onset() const {
    // Golden-section search of the marginal curve, which has one minimum near k = 3.1.
    const double g = 0.5 * (std::sqrt(5.0) - 1);
    double a = 1, b = 7;
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = marginal_reynolds(c), fd = marginal_reynolds(d);
    while (b - a > 1e-7) {
        if (fc < fd) {
            b = d, d = c, fd = fc;
            c = b - g * (b - a), fc = marginal_reynolds(c);
        } else {
            a = c, c = d, fc = fd;
            d = a + g * (b - a), fd = marginal_reynolds(d);
        }
    }
    const double k = 0.5 * (a + b);
    return {marginal_reynolds(k), k};
}

CouetteStability::AdmissibleMode CouetteStability::fastest_admissible_mode(double reynolds, double length,
                                                                           bool periodic) const {
    const double step = (periodic ? 2 : 1) * kPi / length;
    const double k_max = 4 * onset().wavenumber;  // shorter waves are strongly damped
    const int m_max = std::max(1, static_cast<int>(k_max / step));
    AdmissibleMode best;
    auto consider = [&](int m) {
        const double sigma = growth_rate(reynolds, m * step);
        if (best.index == 0 || sigma > best.growth_rate)
            best = {m, m * step, sigma, periodic ? 2 * m : m};
    };
    // A long cylinder admits thousands of modes (4 per gap width of length), ~1 ms each. The
    // growth rate has a single maximum in k (one band of unstable waves), so there the
    // fastest admissible mode is one of those next to the maximum of sigma(k): found by a
    // golden-section search, so the cost no longer grows with the length.
    constexpr int kFullScan = 48;
    if (m_max <= kFullScan) {
        for (int m = 1; m <= m_max; ++m) consider(m);
        return best;
    }
    const double golden = 0.5 * (std::sqrt(5.0) - 1);
    double a = step, b = k_max;
    double c = b - golden * (b - a), d = a + golden * (b - a);
    double fc = growth_rate(reynolds, c), fd = growth_rate(reynolds, d);
    while (b - a > 0.5 * step) {
        if (fc > fd) {
            b = d, d = c, fd = fc;
            c = b - golden * (b - a), fc = growth_rate(reynolds, c);
        } else {
            a = c, c = d, fc = fd;
            d = a + golden * (b - a), fd = growth_rate(reynolds, d);
        }
    }
    const int centre = static_cast<int>(std::lround(0.5 * (a + b) / step));
    for (int m = std::max(1, centre - 2); m <= std::min(m_max, centre + 2); ++m) consider(m);
    return best;
}

}  // namespace emergent
