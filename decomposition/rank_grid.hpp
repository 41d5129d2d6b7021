// SPDX-License-Identifier: MIT
// Cartesian grid of ranks over an orthorhombic box: who owns which sub-box, who is next door.
#pragma once

#include <mpi.h>

#include <vector>

#include "emergent/box.hpp"

namespace emergent::decomp {

/// A 3D Cartesian partition of the global box into sub-boxes, one per rank.
///
/// The grid minimises the surface between sub-boxes (the ghost volume) unless a shape is
/// given. Axes may be excluded from splitting (a scene whose images couple two axes, for
/// instance). The sub-boxes start equal; the planes that cut each axis may then be moved
/// (set_cuts, for load balance), the same planes for every rank: domains stay boxes and
/// their neighbours stay the grid's. Nothing here knows about forces: the ghost width is a
/// number handed in.
class RankGrid {
public:
    /// dims: requested ranks per axis, 0 = choose; split_axis[d] = false keeps axis d whole.
    RankGrid(MPI_Comm comm, const Box& global, Int3 dims = {0, 0, 0},
             const bool split_axis[3] = nullptr);
    ~RankGrid();
    RankGrid(const RankGrid&) = delete;
    RankGrid& operator=(const RankGrid&) = delete;

    MPI_Comm comm() const { return cart_; }
    int rank() const { return rank_; }
    int size() const { return size_; }
    const Box& global() const { return global_; }
    Int3 dims() const { return dims_; }
    Int3 coords() const { return coords_; }
    Vec3 lo() const { return lo_; }
    Vec3 hi() const { return hi_; }

    /// Rank across face (d, side); side 0 = low, 1 = high. MPI_PROC_NULL at a closed wall.
    int neighbour(int d, int side) const { return neighbour_[d][side]; }

    /// True if crossing face (d, side) wraps around the periodic global box.
    bool wraps(int d, int side) const;

    /// Rank whose domain holds x (positions outside the box are clamped to the edge domains).
    int rank_of(const Vec3& x) const;

    /// Throws InputError (collectively) when a sub-box is thinner than the ghost width.
    void require_width(double ghost_width) const;

    /// The dims()[d] + 1 planes cutting axis d, from the box's low to its high face.
    const std::vector<double>& cuts(int d) const { return cuts_[d]; }
    /// Moves the inner planes of axis d (same on every rank; the outer two are the box's
    /// faces). logic_error unless there are dims()[d] + 1 planes, increasing, ending at the box.
    void set_cuts(int d, const std::vector<double>& planes);

    /// Ranks per axis minimising the inter-domain surface for box lengths `length`.
    static Int3 choose_dims(int n_ranks, const Vec3& length, const bool split_axis[3]);

private:
    MPI_Comm cart_ = MPI_COMM_NULL;
    Box global_;
    int rank_ = 0, size_ = 1;
    Int3 dims_{1, 1, 1}, coords_{0, 0, 0};
    Vec3 lo_{}, hi_{};
    std::vector<double> cuts_[3];
    int neighbour_[3][2] = {};
};

}  // namespace emergent::decomp
