// SPDX-License-Identifier: MIT
// Smoothing of periodic 2D fields and their local minima (cell centres).
#include <fftw3.h>

#include <cmath>
#include <complex>

#include "emergent/kit/cell_pattern.hpp"
#include "kit/fftw_array.hpp"

namespace emergent {

namespace {
constexpr double kTwoPi = 6.283185307179586;

/// Signed mode number of index k of an n-point transform.
int mode(int k, int n) { return k <= n / 2 ? k : k - n; }
}  // namespace

PeriodicField2D smooth_periodic(const PeriodicField2D& field, double width) {
    if (!(width > 0) || field.value.empty()) return field;
    const int nx = field.nx, ny = field.ny, nxc = nx / 2 + 1;
    FftwArray<double> data(field.value.size());
    std::copy(field.value.begin(), field.value.end(), data.begin());
    FftwArray<std::complex<double>> spectrum(static_cast<std::size_t>(ny) * nxc);
    auto* out = reinterpret_cast<fftw_complex*>(spectrum.data());
    fftw_plan forward = fftw_plan_dft_r2c_2d(ny, nx, data.data(), out, FFTW_ESTIMATE);
    fftw_plan backward = fftw_plan_dft_c2r_2d(ny, nx, out, data.data(), FFTW_ESTIMATE);
    fftw_execute(forward);
    // Fourier transform of the Gaussian: exp(-k^2 width^2 / 2); 1 / (nx ny) undoes FFTW's scale.
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nxc; ++i) {
            const double kx = kTwoPi * i / field.lx, ky = kTwoPi * mode(j, ny) / field.ly;
            spectrum[static_cast<std::size_t>(j) * nxc + i] *=
                std::exp(-0.5 * (kx * kx + ky * ky) * width * width) / (double(nx) * ny);
        }
    fftw_execute(backward);
    fftw_destroy_plan(forward);
    fftw_destroy_plan(backward);
    PeriodicField2D smoothed = field;
    smoothed.value.assign(data.begin(), data.end());
    return smoothed;
}

std::vector<Point2> local_minima(const PeriodicField2D& f) {
    std::vector<Point2> minima;
    const int nx = f.nx, ny = f.ny;
    if (nx < 3 || ny < 3) return minima;
    auto at = [&](int i, int j) {
        i = (i % nx + nx) % nx, j = (j % ny + ny) % ny;
        return i + nx * j;
    };
    // Strict order with ties broken by index, so two equal neighbours are never both minima
    // (a flat bottom of simple shape yields one).
    auto lower = [&](int a, int b) { return f.value[a] < f.value[b] || (f.value[a] == f.value[b] && a < b); };
    // Vertex of the parabola through (-1, a), (0, b), (1, c), kept within the cell.
    auto vertex = [](double a, double b, double c) {
        const double curvature = a - 2 * b + c;
        if (!(curvature > 0)) return 0.0;
        return std::fmax(-0.5, std::fmin(0.5, 0.5 * (a - c) / curvature));
    };
    const double dx = f.lx / nx, dy = f.ly / ny;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int c = at(i, j);
            bool minimum = true;
            for (int dj = -1; dj <= 1 && minimum; ++dj)
                for (int di = -1; di <= 1; ++di)
                    if ((di || dj) && !lower(c, at(i + di, j + dj))) {
                        minimum = false;
                        break;
                    }
            if (!minimum) continue;
            const double ox = vertex(f.value[at(i - 1, j)], f.value[c], f.value[at(i + 1, j)]);
            const double oy = vertex(f.value[at(i, j - 1)], f.value[c], f.value[at(i, j + 1)]);
            double x = (i + 0.5 + ox) * dx, y = (j + 0.5 + oy) * dy;
            if (x >= f.lx) x -= f.lx;
            if (x < 0) x += f.lx;
            if (y >= f.ly) y -= f.ly;
            if (y < 0) y += f.ly;
            minima.push_back({x, y});
        }
    return minima;
}

}  // namespace emergent
