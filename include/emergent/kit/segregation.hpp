// SPDX-License-Identifier: MIT
// Measures of segregation in a two-species mixture: the fraction of one species in bins along a
// coordinate, a split index with its random-mixture spread, and a census of bands.
#pragma once

#include <mpi.h>

#include <vector>

namespace emergent {

/// Members of a mixture counted in n equal bins of a coordinate over [lo, hi): all of them, and
/// the `marked` ones (e.g. the big particles). Members outside [lo, hi) are not counted.
struct MixtureBins {
    double lo = 0, hi = 1;
    std::vector<double> count, marked;
    /// Marked fraction per bin (NaN where a bin is empty).
    std::vector<double> fraction() const;
};

/// Counts this rank's members (coordinate[i], marked[i]) and sums over `comm`. Collective.
MixtureBins mixture_bins(const std::vector<double>& coordinate, const std::vector<char>& marked,
                         double lo, double hi, int n, MPI_Comm comm);

/// The members split into the half with the smaller coordinate ("inner") and the rest.
/// index = marked fraction inner - marked fraction outer. For a random mixture (labels dealt at
/// random over the same positions) the index has mean 0 and the hypergeometric standard
/// deviation `random_sd`, computed from the counts; `index / random_sd` says how far from
/// random the mixture is.
struct SplitSegregation {
    double index = 0, random_sd = 0;
    double inner_fraction = 0, outer_fraction = 0;
    double split = 0;  ///< coordinate separating the halves
    long long n = 0;
};
SplitSegregation split_segregation(const std::vector<double>& coordinate,
                                   const std::vector<char>& marked, MPI_Comm comm);

/// Bands of alternating composition along the bins (axial segregation). contrast = rms of the
/// bins' marked fraction about the overall fraction, over the rms a random mixture would give
/// (binomial, from each bin's count): about 1 when mixed, large when banded. bands = 1 + the
/// number of composition changes, each between two extremes beyond `threshold` random-mixture
/// standard deviations (count_rolls of flow_analysis.hpp).
struct BandCensus {
    int bands = 1;
    double contrast = 0;
    std::vector<double> boundaries;
};
BandCensus band_census(const MixtureBins& bins, double threshold = 3.0);

}  // namespace emergent
