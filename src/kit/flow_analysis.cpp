// SPDX-License-Identifier: MIT
// Roll census and dominant modes of flow profiles.
#include "emergent/kit/flow_analysis.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>

namespace emergent {

double noise_factor_from_frames(const std::vector<double>& a, const std::vector<double>& model_a,
                                const std::vector<double>& b, const std::vector<double>& model_b) {
    double difference = 0, model = 0;
    const std::size_t n = std::min({a.size(), b.size(), model_a.size(), model_b.size()});
    for (std::size_t k = 0; k < n; ++k) {
        const double d = a[k] - b[k], m = model_a[k] * model_a[k] + model_b[k] * model_b[k];
        if (!std::isfinite(d) || !std::isfinite(m)) continue;
        difference += d * d;
        model += m;
    }
    return model > 0 ? std::max(1.0, std::sqrt(difference / model)) : 1.0;
}

RollCensus count_rolls(const std::vector<double>& velocity, const std::vector<double>& noise,
                       double first, double spacing, double threshold) {
    RollCensus census;
    int last_sign = 0;
    std::size_t last_significant = 0;
    for (std::size_t k = 0; k < velocity.size(); ++k) {
        if (!(noise[k] > 0) || !std::isfinite(velocity[k])) continue;
        if (std::fabs(velocity[k]) < threshold * noise[k]) continue;
        const int sign = velocity[k] > 0 ? 1 : -1;
        if (last_sign && sign != last_sign) {
            // The last zero crossing between the two significant cells.
            double at = first + (0.5 * (last_significant + k)) * spacing;
            for (std::size_t j = k; j > last_significant; --j) {
                const double a = velocity[j - 1], b = velocity[j];
                if (std::isfinite(a) && (a > 0) != (b > 0) && a != b) {
                    at = first + (j - 1 + a / (a - b)) * spacing;
                    break;
                }
            }
            census.centres.push_back(at);
        }
        last_sign = sign;
        last_significant = k;
    }
    census.count = static_cast<int>(census.centres.size());
    return census;
}

DominantMode dominant_mode(const std::vector<double>& profile, double length, bool periodic) {
    DominantMode best;
    const int n = static_cast<int>(profile.size());
    if (n < 2) return best;
    std::vector<double> in(profile);
    if (periodic) {
        std::vector<std::complex<double>> out(n / 2 + 1);
        fftw_plan plan = fftw_plan_dft_r2c_1d(n, in.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                              FFTW_ESTIMATE);
        fftw_execute(plan);
        fftw_destroy_plan(plan);
        for (int m = 1; m < static_cast<int>(out.size()); ++m) {
            // A wave A cos(2 pi m z / L + phi) has |F_m| = A n / 2 (A n at the Nyquist mode).
            const double a = std::abs(out[m]) * (2 * m == n ? 1.0 : 2.0) / n;
            if (a > best.amplitude) best = {m, length / m, a};
        }
    } else {
        std::vector<double> out(n);
        fftw_plan plan = fftw_plan_r2r_1d(n, in.data(), out.data(), FFTW_REDFT10, FFTW_ESTIMATE);
        fftw_execute(plan);
        fftw_destroy_plan(plan);
        for (int m = 1; m < n; ++m) {
            // REDFT10 of A cos(pi m (j + 1/2) / n) is A n at index m.
            const double a = std::fabs(out[m]) / n;
            if (a > best.amplitude) best = {m, 2 * length / m, a};
        }
    }
    return best;
}

}  // namespace emergent
