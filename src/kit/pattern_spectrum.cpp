// SPDX-License-Identifier: MIT
// Shell-binned power spectrum of a periodic 2D field.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "emergent/kit/cell_pattern.hpp"
#include "kit/fftw_array.hpp"

namespace emergent {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}

PatternSpectrum pattern_spectrum(const PeriodicField2D& field) {
    PatternSpectrum result;
    const int nx = field.nx, ny = field.ny, nxc = nx / 2 + 1;
    if (nx < 2 || ny < 2) return result;
    double mean = 0;
    for (double v : field.value) mean += v;
    mean /= field.value.size();
    FftwArray<double> data(field.value.size());
    for (std::size_t k = 0; k < data.size(); ++k) data[k] = field.value[k] - mean;
    FftwArray<std::complex<double>> spectrum(static_cast<std::size_t>(ny) * nxc);
    fftw_plan plan = fftw_plan_dft_r2c_2d(ny, nx, data.data(),
                                          reinterpret_cast<fftw_complex*>(spectrum.data()),
                                          FFTW_ESTIMATE);
    fftw_execute(plan);
    fftw_destroy_plan(plan);

    result.shell_width = kTwoPi / std::max(field.lx, field.ly);
    const double k_max = std::hypot(kTwoPi * (nx / 2) / field.lx, kTwoPi * (ny / 2) / field.ly);
    const int shells = static_cast<int>(k_max / result.shell_width + 0.5) + 1;
    result.shell_power.assign(shells, 0.0);
    std::vector<double> k_weighted(shells, 0.0);
    const double norm = 1.0 / (double(nx) * ny * double(nx) * ny);
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nxc; ++i) {
            const int my = j <= ny / 2 ? j : j - ny;
            const double k = std::hypot(kTwoPi * i / field.lx, kTwoPi * my / field.ly);
            // The half spectrum stands for both k and -k, except on its own edges.
            const double multiplicity = (i == 0 || 2 * i == nx) ? 1.0 : 2.0;
            const double p = multiplicity * std::norm(spectrum[static_cast<std::size_t>(j) * nxc + i]) * norm;
            const int s = static_cast<int>(k / result.shell_width + 0.5);
            if (s < 1 || s >= shells) continue;
            result.shell_power[s] += p;
            k_weighted[s] += p * k;
        }
    for (int s = 1; s < shells; ++s)
        if (result.shell_power[s] > result.shell_power[result.dominant_shell]) result.dominant_shell = s;
    const int s = result.dominant_shell;
    if (s > 0 && result.shell_power[s] > 0)
        result.dominant_wavelength = kTwoPi / (k_weighted[s] / result.shell_power[s]);
    return result;
}

}  // namespace emergent
