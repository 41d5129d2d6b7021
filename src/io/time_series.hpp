// SPDX-License-Identifier: MIT
// An H5MD time-dependent element: {step, time, value} growing by one frame per write.
#pragma once

#include <mpi.h>

#include <vector>

#include "io/h5.hpp"

namespace emergent::io {

/// Group `name` holding `step` [n] (int64), `time` [n] (float64) and `value` [n, frame...].
/// Appending is collective: every rank writes its own rows of the frame's first dimension.
class TimeSeries {
public:
    /// frame: shape of one frame (empty for a scalar per frame).
    TimeSeries(hid_t parent, const std::string& name, hid_t type, std::vector<hsize_t> frame);

    /// Appends one frame. `rows` holds this rank's rows [first_row, first_row + n_rows) of the
    /// frame's first dimension (for a scalar frame: rank 0 passes n_rows = 1, others 0).
    void append(long long step, double time, const void* rows, hsize_t first_row, hsize_t n_rows,
                MPI_Comm comm);

    hsize_t frames() const { return frames_; }
    /// The `value` dataset and its element type (for views of single frames).
    hid_t value() const { return value_; }
    hid_t type() const { return type_; }

private:
    void extend(hid_t set, hsize_t frames);

    H5Id group_, step_, time_, value_;
    hid_t type_;
    std::vector<hsize_t> frame_;
    hsize_t frames_ = 0;
};

}  // namespace emergent::io
