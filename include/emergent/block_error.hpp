// SPDX-License-Identifier: MIT
// The standard error of a correlated series' mean from the scatter of its block means.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace emergent {

/// Standard error of the mean from the first `blocks` contiguous blocks of `length` values of
/// x (Flyvbjerg-Petersen): blocks longer than the series' correlation time have independent
/// means, so their scatter gives an honest error bar. NaN with fewer than two blocks or more
/// blocks than x holds.
inline double block_standard_error(const std::vector<double>& x, std::size_t length, std::size_t blocks) {
    if (blocks < 2 || length == 0 || blocks * length > x.size()) return NAN;
    std::vector<double> means(blocks, 0.0);
    for (std::size_t b = 0; b < blocks; ++b) {
        for (std::size_t k = 0; k < length; ++k) means[b] += x[b * length + k];
        means[b] /= double(length);
    }
    double m = 0;
    for (double v : means) m += v;
    m /= double(blocks);
    double var = 0;
    for (double v : means) var += (v - m) * (v - m);
    var /= double(blocks - 1);
    return std::sqrt(var / double(blocks));
}

}  // namespace emergent
