// SPDX-License-Identifier: MIT
// Id-ordered particle blocks.
#include "io/id_order.hpp"

#include <cstring>
#include <stdexcept>

#include "emergent/error.hpp"
#include "io/h5.hpp"

namespace emergent::io {

namespace {
std::vector<int> destinations(MPI_Comm comm, const std::int64_t* ids, std::size_t n,
                              long long n_global) {
    int n_ranks = 1;
    MPI_Comm_size(comm, &n_ranks);
    const decomp::IdBlocks blocks{n_global, n_ranks};
    std::vector<int> dest(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (ids[i] < 0 || ids[i] >= n_global)
            throw std::logic_error("id-ordered output needs particle ids 0..N-1");
        dest[i] = blocks.owner(ids[i]);
    }
    return dest;
}
}  // namespace

IdOrder::IdOrder(MPI_Comm comm, const std::int64_t* ids, std::size_t n_owned, long long n_global)
    : plan_(comm, destinations(comm, ids, n_owned, n_global)) {
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    const decomp::IdBlocks blocks{n_global, n_ranks};
    first_ = blocks.first(rank);
    count_ = static_cast<std::size_t>(blocks.first(rank + 1) - first_);
    ids_.resize(plan_.n_import());
    plan_.apply(ids, sizeof(std::int64_t), ids_.data());
    if (ids_.size() != count_) throw std::logic_error("id-ordered output: ids are not 0..N-1");
}

std::vector<char> IdOrder::gather(const void* field, std::size_t bytes) const {
    std::vector<char> received(plan_.n_import() * bytes), ordered(count_ * bytes);
    plan_.apply(field, bytes, received.data());
    for (std::size_t k = 0; k < count_; ++k)
        std::memcpy(&ordered[(ids_[k] - first_) * bytes], &received[k * bytes], bytes);
    return ordered;
}

/// Rows [first, first + count) of a dataset of shape {N} or {N, width}, in file and memory
/// (an empty selection on ranks without rows: they still join the collective call).
struct RowSelection {
    H5Id file, memory;
    RowSelection(hid_t set, int width, long long first, std::size_t count) {
        const int rank = width > 0 ? 2 : 1;
        const hsize_t start[2] = {static_cast<hsize_t>(first), 0};
        const hsize_t extent[2] = {count, static_cast<hsize_t>(width)};
        file = H5Id(H5Dget_space(set));
        memory = H5Id(H5Screate_simple(rank, extent, nullptr));
        if (count == 0) {
            H5Sselect_none(file);
            H5Sselect_none(memory);
        } else {
            H5Sselect_hyperslab(file, H5S_SELECT_SET, start, nullptr, extent, nullptr);
        }
    }
};

void write_rows(hid_t parent, const char* name, hid_t type, long long n_global, int width,
                const void* rows, long long first, std::size_t count) {
    const int rank = width > 0 ? 2 : 1;
    const hsize_t dims[2] = {static_cast<hsize_t>(n_global), static_cast<hsize_t>(width)};
    H5Id space(H5Screate_simple(rank, dims, nullptr));
    H5Id set(h5_check(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                      std::string("dataset ") + name));
    const RowSelection rows_here(set, width, first, count);
    H5Id xfer = collective_transfer();
    h5_check(H5Dwrite(set, type, rows_here.memory, rows_here.file, xfer, rows), std::string("write ") + name);
}

void read_rows(hid_t parent, const char* name, hid_t type, int width, void* rows,
               long long first, std::size_t count, long long n_rows) {
    H5Id set(H5Dopen2(parent, name, H5P_DEFAULT));
    // IoError: the checkpoint's reader names the file (restore_checkpoint).
    if (set < 0) throw IoError(std::string("no dataset '") + name + "'");
    {
        // A shape that does not fit would read past the rows or silently leave some behind.
        H5Id space(H5Dget_space(set));
        hsize_t dims[2] = {0, 0};
        const int rank = H5Sget_simple_extent_ndims(space);
        if (rank >= 1 && rank <= 2) H5Sget_simple_extent_dims(space, dims, nullptr);
        const bool fits = rank == (width > 0 ? 2 : 1) && dims[0] == static_cast<hsize_t>(n_rows) &&
                          (width == 0 || dims[1] == static_cast<hsize_t>(width));
        if (!fits)
            throw IoError(std::string("dataset '") + name + "' is not " + std::to_string(n_rows) +
                          (width > 0 ? " x " + std::to_string(width) : std::string()) +
                          ", the rows the checkpoint records");
    }
    const RowSelection rows_here(set, width, first, count);
    H5Id xfer = collective_transfer();
    h5_check(H5Dread(set, type, rows_here.memory, rows_here.file, xfer, rows), std::string("read ") + name);
}

}  // namespace emergent::io
