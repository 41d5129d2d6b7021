// SPDX-License-Identifier: MIT
#include "emergent/kit/planar_noise.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "emergent/error.hpp"
#include "emergent/particle_store.hpp"
#include "emergent/random.hpp"
#include "emergent/simulation.hpp"

namespace emergent {

namespace {
constexpr double kTwoPi = 6.283185307179586;
constexpr double kPi = 3.141592653589793;
}  // namespace

PlanarNoise::PlanarNoise(double lx, double ly, double min_wavelength, double rms,
                         std::uint64_t seed) {
    if (!(lx > 0 && ly > 0 && min_wavelength > 0 && rms >= 0))
        throw InputError("planar noise: widths and shortest wavelength must be positive, rms >= 0");
    // |k| <= 2 pi / min_wavelength; one of each pair (k, -k): ny > 0, or ny = 0 and nx > 0.
    const double kmax = kTwoPi / min_wavelength;
    const int nx_max = static_cast<int>(std::floor(lx / min_wavelength));
    const int ny_max = static_cast<int>(std::floor(ly / min_wavelength));
    for (int ny = 0; ny <= ny_max; ++ny)
        for (int nx = -nx_max; nx <= nx_max; ++nx) {
            if (ny == 0 && nx <= 0) continue;
            const double kx = kTwoPi * nx / lx, ky = kTwoPi * ny / ly;
            if (kx * kx + ky * ky > kmax * kmax * (1 + 1e-12)) continue;
            const auto index = static_cast<std::uint64_t>(modes_.size());
            modes_.push_back({kx, ky, kTwoPi * uniform_open(seed, 0x6e6f697365ULL, index), 0});
        }
    if (modes_.empty()) {
        if (rms > 0)
            throw InputError("planar noise: no mode of the plane has a wavelength of at least " +
                             std::to_string(min_wavelength));
        return;
    }
    // Each cosine has mean square amplitude^2 / 2 over the plane, and distinct modes are
    // orthogonal there.
    const double amplitude = rms * std::sqrt(2.0 / static_cast<double>(modes_.size()));
    for (Mode& m : modes_) m.amplitude = amplitude;
}

double PlanarNoise::operator()(double x, double y) const {
    double sum = 0;
    for (const Mode& m : modes_) sum += m.amplitude * std::cos(m.kx * x + m.ky * y + m.phase);
    return sum;
}

void perturb_layer_temperature(Simulation& sim, const PlanarNoise& noise, double height) {
    ParticleStore& store = sim.particles();
    std::vector<double> factor(store.n_owned());
    double lowest = 1;
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        const Vec3& r = store.position[i];
        const double profile = std::sin(kPi * std::min(1.0, std::max(0.0, r.z / height)));
        factor[i] = 1 + noise(r.x, r.y) * profile;
        lowest = std::min(lowest, factor[i]);
    }
    double global = 0;
    MPI_Allreduce(&lowest, &global, 1, MPI_DOUBLE, MPI_MIN, sim.comm());
    if (!(global > 0)) {
        std::ostringstream msg;
        msg << "temperature perturbation reaches " << global - 1
            << " of the local temperature: lower its amplitude";
        throw InputError(msg.str());
    }
    for (std::size_t i = 0; i < store.n_owned(); ++i)
        store.velocity[i] = std::sqrt(factor[i]) * store.velocity[i];
}

}  // namespace emergent
