// SPDX-License-Identifier: MIT
// The mean of a sampled quantity over whole periods of a drive (vibration cycles), with an
// error bar from blocks of whole periods: a drift measured in a driven system must not depend
// on where in the cycle the run happens to stop.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "emergent/block_error.hpp"

namespace emergent {

/// Samples (time, value) from `start` on, grouped by cycle k = floor((time - start) / period);
/// a cycle counts once a sample of a later one has arrived. Each complete cycle's mean weighs
/// the same.
class CycleAverage {
public:
    CycleAverage(double period = 1, double start = 0) : period_(period), start_(start) {}

    void add(double time, double value) {
        if (!(time >= start_ - 1e-9 * period_)) return;
        // A sample on a cycle's first instant belongs to it, whatever the rounding of time.
        const auto k = static_cast<std::size_t>(std::floor((time - start_) / period_ + 1e-6));
        if (k >= sum_.size()) {
            sum_.resize(k + 1, 0.0);
            count_.resize(k + 1, 0.0);
        }
        sum_[k] += value;
        count_[k] += 1;
    }

    /// Cycles with a later sample after them (those at the end may still be filling).
    std::size_t complete_cycles() const { return sum_.empty() ? 0 : sum_.size() - 1; }

    /// The complete cycles' means (a cycle without samples is left out).
    std::vector<double> cycle_means() const {
        std::vector<double> m;
        for (std::size_t k = 0; k < complete_cycles(); ++k)
            if (count_[k] > 0) m.push_back(sum_[k] / count_[k]);
        return m;
    }

    /// Mean over the complete cycles; NaN without any.
    double mean() const {
        const std::vector<double> m = cycle_means();
        if (m.empty()) return NAN;
        double s = 0;
        for (double x : m) s += x;
        return s / m.size();
    }

    /// Standard error of mean() from contiguous blocks of 2^j cycles, with j the largest that
    /// leaves at least `min_blocks` blocks: the longest blocks the run affords, so that blocks
    /// outlast the correlation time of the cycle means as the run grows (Flyvbjerg-Petersen).
    /// NaN with fewer than min_blocks complete cycles.
    double standard_error(std::size_t min_blocks = 16) const {
        const std::vector<double> m = cycle_means();
        if (m.size() < min_blocks || min_blocks < 2) return NAN;
        std::size_t length = 1;
        while (m.size() / (2 * length) >= min_blocks) length *= 2;
        block_cycles_ = length;
        return block_standard_error(m, length, m.size() / length);
    }
    /// Cycles per block of the last standard_error().
    std::size_t block_cycles() const { return block_cycles_; }

    /// The running sums, for checkpoints: period, start, then (sum, count) per cycle.
    std::vector<double> state() const {
        std::vector<double> s{period_, start_};
        for (std::size_t k = 0; k < sum_.size(); ++k) {
            s.push_back(sum_[k]);
            s.push_back(count_[k]);
        }
        return s;
    }
    /// Restores what state() gave; false (and nothing changed) if it is malformed.
    bool restore(const std::vector<double>& s) {
        if (s.size() < 2 || s.size() % 2 != 0 || !(s[0] > 0)) return false;
        period_ = s[0];
        start_ = s[1];
        sum_.clear();
        count_.clear();
        for (std::size_t k = 2; k < s.size(); k += 2) {
            sum_.push_back(s[k]);
            count_.push_back(s[k + 1]);
        }
        return true;
    }

private:
    double period_, start_;
    std::vector<double> sum_, count_;
    mutable std::size_t block_cycles_ = 0;
};

}  // namespace emergent
