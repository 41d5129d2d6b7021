// SPDX-License-Identifier: MIT
// A small file for watching a run while it goes: the latest fields and the scene's measures.
#pragma once

#include <hdf5.h>

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "emergent/field_grid.hpp"
#include "emergent/problem.hpp"

namespace emergent::io {

/// DIR/snapshot.h5, written by rank 0 through snapshot.h5.tmp and a rename, so a reader never
/// meets a half-written or locked file (the run's own HDF5 files stay open while it runs):
///   attributes scene, step, time, final (1 once the run has ended);
///   /fields/<grid>/{density, velocity, temperature, count}: the latest frame of each field
///     grid, shaped as one frame of fields.h5, with the grid's attributes;
///   /measures/<name>/{step, time, value}: the history of each measure of at most
///     kMaxHistoryWidth components (observables and the scene's; value [n] for a scalar,
///     [n, components] for a short vector such as a segregation index with its random-mixture
///     sd), at most kMaxPoints samples: when full, every other sample is dropped and later ones
///     are kept at half the rate, so a long run's history stays small and spans it all;
///   /latest/<name>: the last value of every measure, vectors included.
/// Written at most once per `seconds` of wall time (0: never) and at the end.
class WatchSnapshot {
public:
    static constexpr std::size_t kMaxPoints = 2048;
    static constexpr std::size_t kMaxHistoryWidth = 4;

    WatchSnapshot(std::string dir, std::string scene, std::vector<FieldGrid> grids, double seconds);

    bool active() const { return seconds_ > 0; }
    void on_fields(std::size_t grid, const FieldFrame& frame);
    void on_measures(long long step, double time, const Measures& measures);
    /// Writes if `seconds` have passed since the last write, or always when `final`.
    void maybe_write(long long step, double time, bool final = false);

private:
    struct Series {
        std::vector<long long> step;
        std::vector<double> time, value;  ///< value: `width` numbers per sample
        std::size_t width = 0;
        long long seen = 0, stride = 1;
        void add(long long s, double t, const std::vector<double>& v);
    };
    void write(long long step, double time, bool final) const;
    void write_contents(hid_t file, long long step, double time, bool final) const;

    std::string dir_, scene_;
    std::vector<FieldGrid> grids_;
    std::vector<FieldFrame> frames_;
    std::vector<bool> have_frame_;
    double seconds_;
    std::map<std::string, Series> history_;
    std::map<std::string, std::vector<double>> latest_;
    std::chrono::steady_clock::time_point last_write_;
    bool written_ = false, changed_ = false;
};

}  // namespace emergent::io
