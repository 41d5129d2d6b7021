// SPDX-License-Identifier: MIT
// Thin, checked helpers over the parallel HDF5 C API.
#pragma once

#include <hdf5.h>
#include <mpi.h>

#include <string>
#include <vector>

namespace emergent::io {

/// Owns one HDF5 identifier and closes it with the right H5*close.
class H5Id {
public:
    H5Id() = default;
    explicit H5Id(hid_t id) : id_(id) {}
    ~H5Id() { reset(); }
    H5Id(H5Id&& o) noexcept : id_(o.id_) { o.id_ = -1; }
    H5Id& operator=(H5Id&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = o.id_;
            o.id_ = -1;
        }
        return *this;
    }
    H5Id(const H5Id&) = delete;
    H5Id& operator=(const H5Id&) = delete;
    operator hid_t() const { return id_; }
    void reset();
    /// Closes a file now; throws IoError "closing 'path': <cause>" if its last writes fail.
    void close_file(const std::string& path);

private:
    hid_t id_ = -1;
};

/// Throws IoError "what: <the system's reason>", or "what: <HDF5's innermost cause>" when the
/// system gave none, when `status` < 0; returns it otherwise.
hid_t h5_check(hid_t status, const std::string& what);

/// A file that could not be written whole: emptied first (so that HDF5's last writes as it
/// closes find room on a full disk), closed, and removed by `remover` (the one rank of a
/// parallel file that removes it). Never throws.
void discard_file(H5Id& file, const std::string& path, bool remover);

/// Whether a file's close failed in this process. HDF5 1.10 then keeps the freed file in its
/// table and crashes when it shuts down (HDFGroup/hdf5#2257): the process must end without
/// shutting HDF5 down (no MPI_Finalize, whose hook does it).
bool h5_file_close_failed();

/// The system's reason for the last failed write, when it is one a person can act on
/// ("No space left on device"), else empty.
std::string system_cause();

/// Turns off HDF5's printing of its error stack (failures become one IoError line each).
void silence_h5_error_stack();

/// Creates (truncating) or opens a file for collective access by all ranks of `comm`.
H5Id create_file(const std::string& path, MPI_Comm comm);
H5Id open_file(const std::string& path, MPI_Comm comm, bool writable);

H5Id create_group(hid_t parent, const std::string& name);
H5Id open_group(hid_t parent, const std::string& name);
bool exists(hid_t parent, const std::string& path);

void write_attribute(hid_t object, const std::string& name, const std::string& value);
void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& v);
void write_attribute(hid_t object, const std::string& name, const std::vector<int>& value);
void write_attribute(hid_t object, const std::string& name, long long value);
void write_attribute(hid_t object, const std::string& name, double value);
std::string read_string_attribute(hid_t object, const std::string& name);
long long read_integer_attribute(hid_t object, const std::string& name);
double read_double_attribute(hid_t object, const std::string& name);

/// Small dataset written whole by rank 0 (all ranks call it: metadata is collective).
void write_small_dataset(hid_t parent, const std::string& name, hid_t type,
                         const std::vector<hsize_t>& shape, const void* data, MPI_Comm comm);

/// A view (an HDF5 virtual dataset, no copy) named `name` in `group` of frame k of
/// `source_set` (at `source_path` in the same file): value[k] of a [frames, ...] time series.
/// XDMF sidecars point at such views, which every ParaView XDMF reader accepts. Collective in a
/// file opened by several ranks.
void add_frame_view(hid_t group, const std::string& name, hid_t source_set,
                    const std::string& source_path, hsize_t k, hid_t type);
/// "000042": the name of frame k's view.
std::string frame_name(std::size_t k);

/// Reads a whole float64 dataset on every rank (collectively); empty if it has no elements.
std::vector<double> read_doubles(hid_t parent, const std::string& name);

/// Transfer property for collective writes and reads.
H5Id collective_transfer();

}  // namespace emergent::io
