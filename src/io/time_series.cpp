// SPDX-License-Identifier: MIT
// Extendible {step, time, value} datasets.
#include "io/time_series.hpp"

#include <algorithm>
#include <tuple>

namespace emergent::io {

namespace {
H5Id extendible(hid_t parent, const char* name, hid_t type, const std::vector<hsize_t>& frame) {
    std::vector<hsize_t> dims{0}, max{H5S_UNLIMITED}, chunk{1};
    for (hsize_t d : frame) {
        dims.push_back(d);
        max.push_back(d);
        chunk.push_back(std::max<hsize_t>(1, d));
    }
    // Chunks of at most ~1M elements per frame keep partial reads cheap on large systems.
    if (chunk.size() > 1) {
        hsize_t elements = 1;
        for (std::size_t k = 2; k < chunk.size(); ++k) elements *= chunk[k];
        chunk[1] = std::max<hsize_t>(1, std::min<hsize_t>(chunk[1], (1u << 20) / elements));
    } else {
        chunk[0] = 1024;  // scalar series: many frames per chunk
    }
    H5Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()));
    H5Id plist(H5Pcreate(H5P_DATASET_CREATE));
    H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data());
    return H5Id(h5_check(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
                         std::string("dataset ") + name));
}
}  // namespace

TimeSeries::TimeSeries(hid_t parent, const std::string& name, hid_t type,
                       std::vector<hsize_t> frame)
    : type_(type), frame_(std::move(frame)) {
    group_ = exists(parent, name) ? open_group(parent, name) : create_group(parent, name);
    step_ = extendible(group_, "step", H5T_NATIVE_LLONG, {});
    time_ = extendible(group_, "time", H5T_NATIVE_DOUBLE, {});
    value_ = extendible(group_, "value", type, frame_);
}

void TimeSeries::extend(hid_t set, hsize_t frames) {
    H5Id space(H5Dget_space(set));
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> dims(rank);
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    dims[0] = frames;
    h5_check(H5Dset_extent(set, dims.data()), "extend time series");
}

void TimeSeries::append(long long step, double time, const void* rows, hsize_t first_row,
                        hsize_t n_rows, MPI_Comm comm) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    const hsize_t k = frames_;
    H5Id xfer = collective_transfer();
    // step and time: rank 0 writes, the others join the collective call with nothing.
    for (auto [set, type, data] : {std::tuple<hid_t, hid_t, const void*>{step_, H5T_NATIVE_LLONG, &step},
                                   {time_, H5T_NATIVE_DOUBLE, &time}}) {
        extend(set, k + 1);
        H5Id file(H5Dget_space(set));
        const hsize_t one = 1;
        H5Sselect_hyperslab(file, H5S_SELECT_SET, &k, nullptr, &one, nullptr);
        H5Id mem(H5Screate_simple(1, &one, nullptr));
        if (rank != 0) {
            H5Sselect_none(file);
            H5Sselect_none(mem);
        }
        h5_check(H5Dwrite(set, type, mem, file, xfer, data), "write step/time");
    }
    extend(value_, k + 1);
    H5Id file(H5Dget_space(value_));
    std::vector<hsize_t> start{k}, count{1};
    if (frame_.empty()) {
        if (n_rows == 0) H5Sselect_none(file);
        else H5Sselect_hyperslab(file, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
    } else {
        start.push_back(first_row);
        count.push_back(n_rows);
        for (std::size_t d = 1; d < frame_.size(); ++d) {
            start.push_back(0);
            count.push_back(frame_[d]);
        }
        if (n_rows == 0) H5Sselect_none(file);
        else H5Sselect_hyperslab(file, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
    }
    hsize_t elements = n_rows;
    for (std::size_t d = 1; d < frame_.size(); ++d) elements *= frame_[d];
    const hsize_t mem_size = std::max<hsize_t>(elements, 1);
    H5Id mem(H5Screate_simple(1, &mem_size, nullptr));
    if (n_rows == 0) H5Sselect_none(mem);
    h5_check(H5Dwrite(value_, type_, mem, file, xfer, rows), "write time series value");
    ++frames_;
}

}  // namespace emergent::io
