// SPDX-License-Identifier: MIT
// Mean and standard error of a correlated time series by block averaging.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "emergent/block_error.hpp"

namespace emergent {

/// Collects samples and reports their mean and the standard error from `n_blocks` contiguous
/// block means (Flyvbjerg–Petersen): blocks longer than the correlation time make the block
/// means independent, so their scatter gives an honest error bar.
class BlockAverage {
public:
    explicit BlockAverage(std::size_t n_blocks = 10) : n_blocks_(n_blocks) {}

    void add(double x) { samples_.push_back(x); }
    std::size_t count() const { return samples_.size(); }
    const std::vector<double>& samples() const { return samples_; }

    double mean() const {
        double s = 0;
        for (double x : samples_) s += x;
        return samples_.empty() ? NAN : s / samples_.size();
    }

    /// Standard error of the mean; NaN with fewer than two samples per block.
    double standard_error() const {
        const std::size_t per_block = samples_.size() / n_blocks_;
        if (per_block < 2) return NAN;
        return block_standard_error(samples_, per_block, n_blocks_);
    }

private:
    std::size_t n_blocks_;
    std::vector<double> samples_;
};

}  // namespace emergent
