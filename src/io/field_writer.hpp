// SPDX-License-Identifier: MIT
// Coarse-grained fields: DIR/fields.h5 plus an XDMF sidecar DIR/fields.xmf for ParaView.
#pragma once

#include <string>
#include <vector>

#include "emergent/field_grid.hpp"
#include "io/h5.hpp"
#include "observe/field_accumulator.hpp"

namespace emergent::io {

/// The grid's description as attributes of `group` (kind, shape, axis names, velocity components,
/// lo/hi; cylindrical grids add axis, r and theta ranges and a `nodes` dataset of their corners).
void write_grid_attributes(hid_t group, const FieldGrid& g);

/// Writes frames of coarse-grained fields. Fields are reduced to rank 0 before writing, so
/// this writer is used by rank 0 alone (serial HDF5 driver): a few kilobytes per frame.
///
/// Layout: /fields/<grid>/{density, velocity, temperature, count}/{step, time, value} with
/// value [frames, n_s, n_theta_or_y, n_r_or_x(, 3)], grid attributes on /fields/<grid>, and
/// per-frame views /fields/<grid>/<quantity>/frames/<k> (HDF5 virtual datasets, no copy) that
/// the XDMF sidecar points at, so every ParaView XDMF reader opens it as a time series.
class FieldWriter {
public:
    /// Writes DIR/STEM.h5 and DIR/STEM.xmf.
    FieldWriter(const std::string& dir, const std::string& stem, const std::vector<FieldGrid>& grids);
    ~FieldWriter();

    /// Appends one frame of grid `g` and rewrites the sidecar (atomically).
    void write(std::size_t g, long long step, double time, const FieldFrame& frame);

private:
    void write_sidecar() const;

    std::string dir_, stem_;
    std::vector<FieldGrid> grids_;
    std::vector<std::vector<std::pair<long long, double>>> frames_;  // per grid: (step, time)
    H5Id file_;
};

}  // namespace emergent::io
