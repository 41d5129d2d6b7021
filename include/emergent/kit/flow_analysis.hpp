// SPDX-License-Identifier: MIT
// Analysis of coarse-grained flow profiles: counting convection rolls and finding the
// dominant spatial mode of a profile.
#pragma once

#include <vector>

namespace emergent {

/// Rolls along a line that crosses a row of counter-rotating vortices through their centres
/// (Taylor vortices at mid-gap along the axis; Rayleigh-Benard rolls at mid-height): the flow
/// component across the line changes sign at each vortex centre.
struct RollCensus {
    int count = 0;                ///< vortex centres found
    std::vector<double> centres;  ///< their positions along the line
};

/// Finds vortex centres in `velocity[k]`, sampled at positions first + k * spacing, with
/// standard errors `noise[k]`: a centre is a sign change between two extremes that each
/// exceed `threshold` standard errors, placed at the last zero crossing between them (by
/// linear interpolation). Cells with a non-positive or non-finite noise are skipped.
RollCensus count_rolls(const std::vector<double>& velocity, const std::vector<double>& noise,
                       double first, double spacing, double threshold = 3.0);

/// How much a model of a profile's standard errors (model[k], e.g. kT/m over the samples of a
/// cell, which ignores that successive samples are correlated) underestimates its real noise,
/// measured from two successive frames of the profile: if the profile itself changed little
/// between them, their difference is noise, with variance model_a^2 + model_b^2 times the
/// factor squared. Returns that factor, at least 1 (a changing profile inflates it: the
/// estimate errs towards more noise). Cells where either value is non-finite are skipped;
/// 1 if none is left.
double noise_factor_from_frames(const std::vector<double>& a, const std::vector<double>& model_a,
                                const std::vector<double>& b, const std::vector<double>& model_b);

/// Strongest non-uniform mode of a profile sampled at n cell centres over a length L.
struct DominantMode {
    int index = 0;          ///< mode number m (0 if the profile is empty or uniform)
    double wavelength = 0;  ///< L / m (periodic) or 2 L / m (bounded)
    double amplitude = 0;   ///< of the cosine/sine wave that mode stands for
};

/// Periodic profiles are expanded in Fourier modes exp(2 pi i m z / L); bounded ones (closed
/// ends with no flux through them) in cosines cos(pi m z / L), by FFTW (r2c or REDFT10).
DominantMode dominant_mode(const std::vector<double>& profile, double length, bool periodic);

}  // namespace emergent
