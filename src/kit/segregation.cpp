// SPDX-License-Identifier: MIT
// Segregation measures of a two-species mixture.
#include "emergent/kit/segregation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "emergent/error.hpp"
#include "emergent/kit/flow_analysis.hpp"

namespace emergent {

std::vector<double> MixtureBins::fraction() const {
    std::vector<double> f(count.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = 0; k < count.size(); ++k)
        if (count[k] > 0) f[k] = marked[k] / count[k];
    return f;
}

MixtureBins mixture_bins(const std::vector<double>& coordinate, const std::vector<char>& marked,
                         double lo, double hi, int n, MPI_Comm comm) {
    if (n < 1 || !(hi > lo)) throw InputError("mixture bins: need n >= 1 bins over hi > lo");
    MixtureBins b;
    b.lo = lo, b.hi = hi;
    std::vector<double> local(2 * n, 0.0);
    const double scale = n / (hi - lo);
    for (std::size_t i = 0; i < coordinate.size(); ++i) {
        const double u = (coordinate[i] - lo) * scale;
        if (!(u >= 0) || !(u < n)) continue;
        const int k = static_cast<int>(u);
        local[k] += 1;
        local[n + k] += marked[i] ? 1 : 0;
    }
    std::vector<double> global(2 * n);
    MPI_Allreduce(local.data(), global.data(), 2 * n, MPI_DOUBLE, MPI_SUM, comm);
    b.count.assign(global.begin(), global.begin() + n);
    b.marked.assign(global.begin() + n, global.end());
    return b;
}

SplitSegregation split_segregation(const std::vector<double>& coordinate,
                                   const std::vector<char>& marked, MPI_Comm comm) {
    // The split needs the global order of the coordinates: gather them (one double per member,
    // at sampling steps only), marked members carrying a flag in the sign of a second array.
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    const int mine = static_cast<int>(coordinate.size());
    std::vector<int> counts(ranks), offsets(ranks, 0);
    MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    const int total = offsets.back() + counts.back();
    std::vector<double> x(total);
    std::vector<char> m(total);
    MPI_Allgatherv(coordinate.data(), mine, MPI_DOUBLE, x.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, comm);
    MPI_Allgatherv(marked.data(), mine, MPI_CHAR, m.data(), counts.data(), offsets.data(),
                   MPI_CHAR, comm);
    SplitSegregation s;
    s.n = total;
    if (total < 2) return s;
    // Order by coordinate, ties by mark, so the split is the same on every rank count.
    std::vector<int> order(total);
    for (int i = 0; i < total; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return x[a] != x[b] ? x[a] < x[b] : m[a] < m[b];
    });
    const long long n_in = total / 2, n_out = total - n_in;
    long long in_marked = 0, all_marked = 0;
    for (int k = 0; k < total; ++k) {
        const int i = order[k];
        all_marked += m[i] ? 1 : 0;
        if (k < n_in) in_marked += m[i] ? 1 : 0;
    }
    s.split = 0.5 * (x[order[n_in - 1]] + x[order[n_in]]);
    s.inner_fraction = double(in_marked) / n_in;
    s.outer_fraction = double(all_marked - in_marked) / n_out;
    s.index = s.inner_fraction - s.outer_fraction;
    // Marked count in the inner half of a random mixture: hypergeometric (N, K, n_in), variance
    // n_in p (1 - p) (N - n_in) / (N - 1); the index is that count times 1/n_in + 1/n_out.
    const double N = total, p = all_marked / N;
    const double var_in = n_in * p * (1 - p) * (N - n_in) / (N - 1);
    s.random_sd = (1.0 / n_in + 1.0 / n_out) * std::sqrt(var_in);
    return s;
}

BandCensus band_census(const MixtureBins& bins, double threshold) {
    BandCensus c;
    const int n = static_cast<int>(bins.count.size());
    double all = 0, marked = 0;
    for (int k = 0; k < n; ++k) all += bins.count[k], marked += bins.marked[k];
    if (n == 0 || all <= 0) return c;
    const double p = marked / all, width = (bins.hi - bins.lo) / n;
    std::vector<double> deviation(n, 0.0), noise(n, 0.0);
    double observed = 0, random = 0;
    for (int k = 0; k < n; ++k) {
        if (bins.count[k] <= 0) continue;
        deviation[k] = bins.marked[k] / bins.count[k] - p;
        noise[k] = std::sqrt(p * (1 - p) / bins.count[k]);
        observed += deviation[k] * deviation[k];
        random += noise[k] * noise[k];
    }
    c.contrast = random > 0 ? std::sqrt(observed / random) : 0.0;
    const RollCensus changes = count_rolls(deviation, noise, bins.lo + 0.5 * width, width, threshold);
    c.bands = 1 + changes.count;
    c.boundaries = changes.centres;
    return c;
}

}  // namespace emergent
