// SPDX-License-Identifier: MIT
// Checked parallel-HDF5 helpers.
#include "io/h5.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "emergent/error.hpp"

namespace emergent::io {

namespace {
bool g_close_failed = false;
std::string innermost_h5_error();
}  // namespace

bool h5_file_close_failed() { return g_close_failed; }

std::string system_cause() {
    const int e = errno;
    // Only the reasons of a failed write: others (ENOENT from an earlier probe) may be stale.
    const bool write_failure = e == ENOSPC || e == EDQUOT || e == EFBIG || e == EIO || e == EROFS;
    return write_failure ? std::string(std::strerror(e)) : std::string();
}

void H5Id::close_file(const std::string& path) {
    if (id_ < 0) return;
    const hid_t id = id_;
    id_ = -1;
    if (H5Fclose(id) < 0) {
        g_close_failed = true;
        const std::string cause = system_cause();  // before anything else may set errno
        const std::string h5 = innermost_h5_error();
        throw IoError("closing '" + path + "': " + (cause.empty() ? h5 : cause));
    }
}

void discard_file(H5Id& file, const std::string& path, bool remover) {
    if (remover) (void)::truncate(path.c_str(), 0);
    file.reset();
    if (remover) std::remove(path.c_str());
}

void H5Id::reset() {
    if (id_ < 0) return;
    switch (H5Iget_type(id_)) {
        case H5I_FILE:
            if (H5Fclose(id_) < 0) g_close_failed = true;
            break;
        case H5I_GROUP: H5Gclose(id_); break;
        case H5I_DATASET: H5Dclose(id_); break;
        case H5I_DATASPACE: H5Sclose(id_); break;
        case H5I_DATATYPE: H5Tclose(id_); break;
        case H5I_ATTR: H5Aclose(id_); break;
        case H5I_GENPROP_LST: H5Pclose(id_); break;
        default: break;
    }
    id_ = -1;
}

namespace {
/// The innermost entry of HDF5's error stack (the cause, e.g. "unable to open file" or a
/// system error), so a failure reads as one line instead of HDF5's printed stack.
std::string innermost_h5_error() {
    std::string cause;
    H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD,
             [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
                 auto& text = *static_cast<std::string*>(out);
                 if (text.empty() && e->desc && *e->desc) text = e->desc;
                 return 0;
             },
             &cause);
    H5Eclear2(H5E_DEFAULT);
    return cause.empty() ? "HDF5 call failed" : cause;
}
}  // namespace

void silence_h5_error_stack() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

hid_t h5_check(hid_t status, const std::string& what) {
    if (status >= 0) return status;
    const std::string cause = system_cause();  // before anything else may set errno
    const std::string h5 = innermost_h5_error();
    throw IoError(cause.empty() ? what + ": " + h5 : cause + " (" + what + ")");
}

namespace {
H5Id file_access(MPI_Comm comm) {
    H5Id fapl(h5_check(H5Pcreate(H5P_FILE_ACCESS), "file access list"));
    h5_check(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL), "MPI-IO driver");
    // Metadata written collectively: every rank must make the same metadata calls.
    H5Pset_all_coll_metadata_ops(fapl, true);
    H5Pset_coll_metadata_write(fapl, true);
    return fapl;
}

H5Id string_type(std::size_t length) {
    H5Id type(H5Tcopy(H5T_C_S1));
    H5Tset_size(type, length == 0 ? 1 : length);
    H5Tset_strpad(type, H5T_STR_NULLTERM);
    H5Tset_cset(type, H5T_CSET_UTF8);
    return type;
}

void write_raw_attribute(hid_t object, const std::string& name, hid_t type, hid_t space,
                         const void* data) {
    if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
    H5Id attr(h5_check(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                       "attribute " + name));
    h5_check(H5Awrite(attr, type, data), "attribute " + name);
}
}  // namespace

H5Id create_file(const std::string& path, MPI_Comm comm) {
    H5Id fapl = file_access(comm);
    const hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
    if (f < 0) {
        const std::string cause = system_cause();
        const std::string h5 = innermost_h5_error();
        throw IoError("cannot create HDF5 file '" + path + "': " + (cause.empty() ? h5 : cause));
    }
    return H5Id(f);
}

H5Id open_file(const std::string& path, MPI_Comm comm, bool writable) {
    H5Id fapl = file_access(comm);
    hid_t f = -1;
    H5E_BEGIN_TRY { f = H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl); }
    H5E_END_TRY;
    if (f < 0) throw InputError("cannot open '" + path + "': missing, truncated or not HDF5");
    return H5Id(f);
}

void add_frame_view(hid_t group, const std::string& name, hid_t source_set,
                    const std::string& source_path, hsize_t k, hid_t type) {
    H5Id src_space(H5Dget_space(source_set));
    const int rank = H5Sget_simple_extent_ndims(src_space);
    std::vector<hsize_t> dims(rank), start(rank, 0), count(rank);
    H5Sget_simple_extent_dims(src_space, dims.data(), nullptr);
    start[0] = k;
    count = dims;
    count[0] = 1;
    H5Sselect_hyperslab(src_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
    H5Id view_space(H5Screate_simple(rank - 1, dims.data() + 1, nullptr));
    H5Id dcpl(H5Pcreate(H5P_DATASET_CREATE));
    h5_check(H5Pset_virtual(dcpl, view_space, ".", source_path.c_str(), src_space), "frame view");
    H5Id view(h5_check(H5Dcreate2(group, name.c_str(), type, view_space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                       "frame view " + name));
}

std::string frame_name(std::size_t k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%06zu", k);
    return buf;
}

H5Id create_group(hid_t parent, const std::string& name) {
    return H5Id(h5_check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                         "group " + name));
}

H5Id open_group(hid_t parent, const std::string& name) {
    return H5Id(h5_check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "group " + name));
}

bool exists(hid_t parent, const std::string& path) {
    // Check each component, as H5Lexists requires its parents to exist.
    std::string partial;
    std::size_t start = 0;
    while (start <= path.size()) {
        const std::size_t slash = path.find('/', start);
        partial = path.substr(0, slash == std::string::npos ? path.size() : slash);
        if (!partial.empty() && H5Lexists(parent, partial.c_str(), H5P_DEFAULT) <= 0) return false;
        if (slash == std::string::npos) break;
        start = slash + 1;
    }
    return true;
}

void write_attribute(hid_t object, const std::string& name, const std::string& value) {
    H5Id type = string_type(value.size());
    H5Id space(H5Screate(H5S_SCALAR));
    write_raw_attribute(object, name, type, space, value.c_str());
}

void write_attribute(hid_t object, const std::string& name, const std::vector<std::string>& v) {
    std::size_t width = 1;
    for (const auto& s : v) width = std::max(width, s.size() + 1);
    std::vector<char> packed(width * v.size(), '\0');
    for (std::size_t k = 0; k < v.size(); ++k) v[k].copy(&packed[k * width], v[k].size());
    H5Id type = string_type(width);
    const hsize_t n = v.size();
    H5Id space(H5Screate_simple(1, &n, nullptr));
    write_raw_attribute(object, name, type, space, packed.data());
}

void write_attribute(hid_t object, const std::string& name, const std::vector<int>& value) {
    const hsize_t n = value.size();
    H5Id space(H5Screate_simple(1, &n, nullptr));
    write_raw_attribute(object, name, H5T_NATIVE_INT, space, value.data());
}

void write_attribute(hid_t object, const std::string& name, long long value) {
    H5Id space(H5Screate(H5S_SCALAR));
    write_raw_attribute(object, name, H5T_NATIVE_LLONG, space, &value);
}

void write_attribute(hid_t object, const std::string& name, double value) {
    H5Id space(H5Screate(H5S_SCALAR));
    write_raw_attribute(object, name, H5T_NATIVE_DOUBLE, space, &value);
}

std::string read_string_attribute(hid_t object, const std::string& name) {
    H5Id attr(h5_check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "attribute " + name));
    H5Id type(H5Aget_type(attr));
    if (H5Tget_class(type) != H5T_STRING) throw InputError("attribute " + name + " is not text");
    if (H5Tis_variable_str(type) > 0) {
        char* text = nullptr;
        H5Id memtype(H5Tcopy(H5T_C_S1));
        H5Tset_size(memtype, H5T_VARIABLE);
        h5_check(H5Aread(attr, memtype, &text), "attribute " + name);
        std::string out = text ? text : "";
        H5free_memory(text);
        return out;
    }
    std::vector<char> buf(H5Tget_size(type) + 1, '\0');
    h5_check(H5Aread(attr, type, buf.data()), "attribute " + name);
    return std::string(buf.data());
}

long long read_integer_attribute(hid_t object, const std::string& name) {
    H5Id attr(h5_check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "attribute " + name));
    long long v = 0;
    h5_check(H5Aread(attr, H5T_NATIVE_LLONG, &v), "attribute " + name);
    return v;
}

double read_double_attribute(hid_t object, const std::string& name) {
    H5Id attr(h5_check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "attribute " + name));
    double v = 0;
    h5_check(H5Aread(attr, H5T_NATIVE_DOUBLE, &v), "attribute " + name);
    return v;
}

void write_small_dataset(hid_t parent, const std::string& name, hid_t type,
                         const std::vector<hsize_t>& shape, const void* data, MPI_Comm comm) {
    H5Id space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr));
    H5Id set(h5_check(H5Dcreate2(parent, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT,
                                 H5P_DEFAULT),
                      "dataset " + name));
    hsize_t elements = 1;
    for (hsize_t d : shape) elements *= d;
    if (elements == 0) return;  // an empty dataset has nothing to write (and no storage)
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    H5Id xfer = collective_transfer();
    H5Id file_space(H5Dget_space(set));
    if (rank != 0) H5Sselect_none(file_space);
    H5Id mem_space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr));
    if (rank != 0) H5Sselect_none(mem_space);
    h5_check(H5Dwrite(set, type, mem_space, file_space, xfer, data), "dataset " + name);
}

std::vector<double> read_doubles(hid_t parent, const std::string& name) {
    H5Id set(h5_check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "dataset " + name));
    H5Id space(H5Dget_space(set));
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    if (!values.empty()) {
        H5Id xfer = collective_transfer();
        h5_check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, xfer, values.data()),
                 "dataset " + name);
    }
    return values;
}

H5Id collective_transfer() {
    H5Id xfer(H5Pcreate(H5P_DATASET_XFER));
    H5Pset_dxpl_mpio(xfer, H5FD_MPIO_COLLECTIVE);
    return xfer;
}

}  // namespace emergent::io
