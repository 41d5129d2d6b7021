// SPDX-License-Identifier: MIT
// Cartesian rank grid.
#include "rank_grid.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <sstream>

#include "emergent/error.hpp"

namespace emergent::decomp {

Int3 RankGrid::choose_dims(int n, const Vec3& length, const bool split_axis[3]) {
    Int3 best{0, 0, 0};
    double best_area = std::numeric_limits<double>::max();
    for (int px = 1; px <= n; ++px) {
        if (n % px || (px > 1 && !split_axis[0])) continue;
        for (int py = 1; py <= n / px; ++py) {
            if ((n / px) % py || (py > 1 && !split_axis[1])) continue;
            const int pz = n / px / py;
            if (pz > 1 && !split_axis[2]) continue;
            const double ax = length.x / px, ay = length.y / py, az = length.z / pz;
            // Surface of one sub-box: what its ghost shell scales with.
            const double area = ax * ay + ay * az + az * ax;
            if (area < best_area * (1 - 1e-12)) {
                best_area = area;
                best = {px, py, pz};
            }
        }
    }
    if (best.x == 0) {
        std::ostringstream msg;
        msg << "grid: " << n << " ranks cannot be arranged along the axes this scene allows";
        throw InputError(msg.str());
    }
    return best;
}

RankGrid::RankGrid(MPI_Comm comm, const Box& global, Int3 dims, const bool split_axis[3])
    : global_(global) {
    const bool all[3] = {true, true, true};
    if (!split_axis) split_axis = all;
    int n = 1;
    MPI_Comm_size(comm, &n);
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
        dims_ = choose_dims(n, global.length(), split_axis);
    } else {
        if (dims.x * dims.y * dims.z != n) {
            std::ostringstream msg;
            msg << "grid=" << dims.x << "x" << dims.y << "x" << dims.z << " has "
                << dims.x * dims.y * dims.z << " domains but the run has " << n << " ranks";
            throw InputError(msg.str());
        }
        for (int d = 0; d < 3; ++d)
            if (dims[d] > 1 && !split_axis[d])
                throw InputError("grid: this scene cannot be split along axis " +
                                 std::string(1, "xyz"[d]));
        dims_ = dims;
    }
    int mpi_dims[3] = {dims_.x, dims_.y, dims_.z};
    int periods[3] = {global.periodic[0], global.periodic[1], global.periodic[2]};
    // No reordering: rank numbers stay those of `comm`, so output order is predictable.
    MPI_Cart_create(comm, 3, mpi_dims, periods, 0, &cart_);
    MPI_Comm_rank(cart_, &rank_);
    MPI_Comm_size(cart_, &size_);
    int c[3];
    MPI_Cart_coords(cart_, rank_, 3, c);
    coords_ = {c[0], c[1], c[2]};
    const Vec3 len = global.length();
    for (int d = 0; d < 3; ++d) {
        cuts_[d].resize(static_cast<std::size_t>(dims_[d]) + 1);
        for (int k = 0; k < dims_[d]; ++k) cuts_[d][k] = global.lo[d] + len[d] * k / dims_[d];
        cuts_[d][dims_[d]] = global.hi[d];
        lo_[d] = cuts_[d][coords_[d]];
        hi_[d] = cuts_[d][coords_[d] + 1];
        MPI_Cart_shift(cart_, d, 1, &neighbour_[d][0], &neighbour_[d][1]);
    }
}

void RankGrid::set_cuts(int d, const std::vector<double>& planes) {
    bool fits = planes.size() == cuts_[d].size() && planes.front() == global_.lo[d] &&
                planes.back() == global_.hi[d];
    for (std::size_t k = 1; fits && k < planes.size(); ++k) fits = planes[k] > planes[k - 1];
    if (!fits) throw std::logic_error("RankGrid::set_cuts: planes do not partition the axis");
    cuts_[d] = planes;
    lo_[d] = cuts_[d][coords_[d]];
    hi_[d] = cuts_[d][coords_[d] + 1];
}

RankGrid::~RankGrid() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized && cart_ != MPI_COMM_NULL) MPI_Comm_free(&cart_);
}

bool RankGrid::wraps(int d, int side) const {
    if (!global_.periodic[d]) return false;
    return side == 0 ? coords_[d] == 0 : coords_[d] == dims_[d] - 1;
}

int RankGrid::rank_of(const Vec3& x) const {
    int c[3];
    for (int d = 0; d < 3; ++d) {
        // The domain [cuts k, cuts k+1) holding x: the same planes lo_/hi_ are, so the two agree.
        const auto inner_begin = cuts_[d].begin() + 1, inner_end = cuts_[d].end() - 1;
        c[d] = static_cast<int>(std::upper_bound(inner_begin, inner_end, x[d]) - inner_begin);
    }
    int rank = 0;
    MPI_Cart_rank(cart_, c, &rank);
    return rank;
}

void RankGrid::require_width(double ghost_width) const {
    for (int d = 0; d < 3; ++d) {
        double width = global_.length()[d];
        for (int k = 0; k < dims_[d]; ++k) width = std::min(width, cuts_[d][k + 1] - cuts_[d][k]);
        if (width < ghost_width) {
            std::ostringstream msg;
            // Unsplit, the box itself is too thin: fewer ranks would not help.
            if (dims_[d] == 1)
                msg << "box too thin: axis " << "xyz"[d] << " is " << width
                    << " wide, less than the ghost shell " << ghost_width
                    << " (cutoff + skin); enlarge the system (the scene's size parameters)";
            else
                msg << "domain too thin: axis " << "xyz"[d] << " is split into " << dims_[d]
                    << " domains, the thinnest of width " << width << ", less than the ghost shell "
                    << ghost_width << " (cutoff + skin); use fewer ranks or a larger system";
            throw InputError(msg.str());
        }
    }
}

}  // namespace emergent::decomp
