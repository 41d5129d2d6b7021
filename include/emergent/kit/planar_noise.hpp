// SPDX-License-Identifier: MIT
// A smooth random field on a periodic plane, to seed an instability that picks its own
// wavelength (e.g. convection cells) instead of waiting for thermal noise to grow.
#pragma once

#include <cstdint>
#include <vector>

namespace emergent {

class Simulation;

/// The sum of every Fourier mode of the periodic lx x ly plane whose wavelength is at least
/// `min_wavelength` (the mean excluded), with equal amplitudes and phases drawn from `seed`:
/// white noise low-pass filtered at that wavelength, so no wavelength inside the band is
/// favoured. Scaled so its rms over the plane is `rms`. Depends only on (lx, ly,
/// min_wavelength, rms, seed), never on the rank.
class PlanarNoise {
public:
    PlanarNoise(double lx, double ly, double min_wavelength, double rms, std::uint64_t seed);

    double operator()(double x, double y) const;

    /// Number of modes summed (each with its mirror -k, which it represents).
    std::size_t modes() const { return modes_.size(); }

    /// The largest |value| the field can take (sum of the mode amplitudes).
    double bound() const { return modes_.empty() ? 0.0 : modes_.front().amplitude * modes_.size(); }

private:
    struct Mode {
        double kx, ky, phase, amplitude;
    };
    std::vector<Mode> modes_;  ///< all of the same amplitude
};

/// Scales the velocities of the particles between two horizontal walls at z = 0 and
/// z = height so the local temperature becomes T (1 + noise(x, y) sin(pi z / height)): a
/// temperature perturbation that vanishes at the walls. Throws InputError on every rank, before
/// changing anything, when the factor would reach zero somewhere (a negative temperature).
void perturb_layer_temperature(Simulation& sim, const PlanarNoise& noise, double height);

}  // namespace emergent
