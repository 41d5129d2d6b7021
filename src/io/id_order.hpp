// SPDX-License-Identifier: MIT
// Particle data in global id order, one contiguous id block per rank: the layout of files.
#pragma once

#include <hdf5.h>
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "decomposition/distributor.hpp"

namespace emergent::io {

/// Plan that brings owned particles' data to the rank writing their id block, in id order.
/// Ids must be exactly 0..N-1 over all ranks.
class IdOrder {
public:
    IdOrder(MPI_Comm comm, const std::int64_t* ids, std::size_t n_owned, long long n_global);

    long long first() const { return first_; }
    std::size_t count() const { return count_; }

    /// This rank's id block of a per-particle field with `bytes` per particle.
    std::vector<char> gather(const void* field, std::size_t bytes) const;

private:
    decomp::Distributor plan_;
    long long first_ = 0;
    std::size_t count_ = 0;
    std::vector<std::int64_t> ids_;
};

/// Creates dataset `name` of shape {n_global, width} (width 0: {n_global}) and writes rows
/// [first, first + count) from each rank. Collective.
void write_rows(hid_t parent, const char* name, hid_t type, long long n_global, int width,
                const void* rows, long long first, std::size_t count);

/// Reads rows [first, first + count) of a dataset of shape {n_rows} or {n_rows, width};
/// IoError, the same on every rank, if it is missing or its shape is another. Collective.
void read_rows(hid_t parent, const char* name, hid_t type, int width, void* rows,
               long long first, std::size_t count, long long n_rows);

}  // namespace emergent::io
