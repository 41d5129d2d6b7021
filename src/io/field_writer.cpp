// SPDX-License-Identifier: MIT
// Field frames and their XDMF sidecar.
#include "io/field_writer.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "emergent/error.hpp"
#include "io/atomic_file.hpp"

namespace emergent::io {

namespace {
const char* const kQuantities[] = {"density", "velocity", "temperature", "count"};

std::vector<hsize_t> frame_shape(const FieldGrid& g, bool vector) {
    std::vector<hsize_t> s{static_cast<hsize_t>(g.n.z), static_cast<hsize_t>(g.n.y),
                           static_cast<hsize_t>(g.n.x)};
    if (vector) s.push_back(3);
    return s;
}

H5Id extendible(hid_t parent, const char* name, hid_t type, const std::vector<hsize_t>& frame) {
    std::vector<hsize_t> dims{0}, max{H5S_UNLIMITED}, chunk{frame.empty() ? hsize_t(64) : 1};
    for (hsize_t d : frame) dims.push_back(d), max.push_back(d), chunk.push_back(d);
    H5Id space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()));
    H5Id plist(H5Pcreate(H5P_DATASET_CREATE));
    H5Pset_chunk(plist, static_cast<int>(chunk.size()), chunk.data());
    return H5Id(h5_check(H5Dcreate2(parent, name, type, space, H5P_DEFAULT, plist, H5P_DEFAULT),
                         std::string("dataset ") + name));
}

/// Appends one frame (all of it) to an extendible dataset.
void append(hid_t set, hid_t type, const void* data, hsize_t frame_index) {
    H5Id space(H5Dget_space(set));
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> dims(rank), start(rank, 0), count(rank);
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    dims[0] = frame_index + 1;
    h5_check(H5Dset_extent(set, dims.data()), "extend field");
    H5Id file(H5Dget_space(set));
    start[0] = frame_index;
    count = dims;
    count[0] = 1;
    H5Sselect_hyperslab(file, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
    hsize_t n = 1;
    for (int d = 1; d < rank; ++d) n *= dims[d];
    H5Id mem(H5Screate_simple(1, &n, nullptr));
    h5_check(H5Dwrite(set, type, mem, file, H5P_DEFAULT, data), "write field");
}

/// A view of frame k of `source` (path inside the same file) as its own dataset.
std::string dims_text(const std::vector<hsize_t>& d) {
    std::ostringstream o;
    for (std::size_t k = 0; k < d.size(); ++k) o << (k ? " " : "") << d[k];
    return o.str();
}
}  // namespace

void write_grid_attributes(hid_t group, const FieldGrid& g) {
    const bool cyl = g.kind == FieldGrid::Kind::Cylindrical;
    write_attribute(group, "kind", std::string(cyl ? "cylindrical" : "cartesian"));
    write_attribute(group, "shape", std::vector<int>{g.n.x, g.n.y, g.n.z});
    write_attribute(group, "axis_names",
                    cyl ? std::vector<std::string>{"r", "theta", "s"}
                        : std::vector<std::string>{"x", "y", "z"});
    // Velocity components follow the grid's axes: (v_r, v_theta, v_s) on cylindrical grids.
    write_attribute(group, "velocity_components",
                    cyl ? std::vector<std::string>{"r", "theta", "s"}
                        : std::vector<std::string>{"x", "y", "z"});
    const double lo[3] = {g.lo.x, g.lo.y, g.lo.z}, hi[3] = {g.hi.x, g.hi.y, g.hi.z};
    const hsize_t three = 3;
    H5Id vec(H5Screate_simple(1, &three, nullptr));
    for (auto [name, data] : {std::pair<const char*, const double*>{"lo", lo}, {"hi", hi}}) {
        H5Id a(H5Acreate2(group, name, H5T_NATIVE_DOUBLE, vec, H5P_DEFAULT, H5P_DEFAULT));
        H5Awrite(a, H5T_NATIVE_DOUBLE, data);
    }
    if (cyl) {
        write_attribute(group, "axis", static_cast<long long>(g.axis));
        write_attribute(group, "r_min", g.r_min);
        write_attribute(group, "r_max", g.r_max);
        write_attribute(group, "theta_min", g.theta_min);
        write_attribute(group, "theta_max", g.theta_max);
        // Node coordinates for a curvilinear mesh in ParaView: [n_s+1][n_theta+1][n_r+1][3].
        std::vector<double> nodes;
        const int a = g.axis, b = (a + 1) % 3, c = (a + 2) % 3;
        for (int is = 0; is <= g.n.z; ++is)
            for (int it = 0; it <= g.n.y; ++it)
                for (int ir = 0; ir <= g.n.x; ++ir) {
                    const double r = g.r_min + (g.r_max - g.r_min) * ir / g.n.x;
                    const double t = g.theta_min + (g.theta_max - g.theta_min) * it / g.n.y;
                    double p[3];
                    p[a] = g.lo[a] + (g.hi[a] - g.lo[a]) * is / g.n.z;
                    p[b] = g.lo[b] + r * std::cos(t);
                    p[c] = g.lo[c] + r * std::sin(t);
                    nodes.insert(nodes.end(), {p[0], p[1], p[2]});
                }
        const hsize_t nd[4] = {static_cast<hsize_t>(g.n.z + 1), static_cast<hsize_t>(g.n.y + 1),
                               static_cast<hsize_t>(g.n.x + 1), 3};
        H5Id space(H5Screate_simple(4, nd, nullptr));
        H5Id set(H5Dcreate2(group, "nodes", H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT,
                            H5P_DEFAULT));
        h5_check(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, nodes.data()),
                 "grid nodes");
    }
}

FieldWriter::FieldWriter(const std::string& dir, const std::string& stem,
                         const std::vector<FieldGrid>& grids)
    : dir_(dir), stem_(stem), grids_(grids), frames_(grids.size()) {
    const std::string path = dir + "/" + stem + ".h5";
    file_ = H5Id(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT));
    if (file_ < 0) throw IoError("cannot create '" + path + "'" + (system_cause().empty() ? "" : ": " + system_cause()));
    H5Id fields = create_group(file_, "fields");
    for (const FieldGrid& g : grids) {
        H5Id group = create_group(fields, g.name);
        write_grid_attributes(group, g);
        for (const char* q : kQuantities) {
            H5Id qg = create_group(group, q);
            extendible(qg, "step", H5T_NATIVE_LLONG, {});
            extendible(qg, "time", H5T_NATIVE_DOUBLE, {});
            extendible(qg, "value", H5T_NATIVE_DOUBLE, frame_shape(g, std::string(q) == "velocity"));
            create_group(qg, "frames");
        }
    }
    h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush");
}

FieldWriter::~FieldWriter() = default;

void FieldWriter::write(std::size_t g, long long step, double time, const FieldFrame& frame) {
    const FieldGrid& grid = grids_.at(g);
    const hsize_t k = frames_[g].size();
    H5Id group = open_group(file_, "fields/" + grid.name);
    const std::vector<double>* data[] = {&frame.density, &frame.velocity, &frame.temperature,
                                         &frame.count};
    for (int q = 0; q < 4; ++q) {
        H5Id qg = open_group(group, kQuantities[q]);
        H5Id step_set(H5Dopen2(qg, "step", H5P_DEFAULT));
        append(step_set, H5T_NATIVE_LLONG, &step, k);
        H5Id time_set(H5Dopen2(qg, "time", H5P_DEFAULT));
        append(time_set, H5T_NATIVE_DOUBLE, &time, k);
        H5Id value(H5Dopen2(qg, "value", H5P_DEFAULT));
        append(value, H5T_NATIVE_DOUBLE, data[q]->data(), k);
        H5Id frames = open_group(qg, "frames");
        add_frame_view(frames, frame_name(k), value,
                       "/fields/" + grid.name + "/" + kQuantities[q] + "/value", k, H5T_NATIVE_DOUBLE);
    }
    h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush");
    frames_[g].push_back({step, time});
    write_sidecar();
}

void FieldWriter::write_sidecar() const {
    std::ostringstream x;
    x.precision(17);
    x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf Version=\"2.0\">\n <Domain>\n";
    for (std::size_t g = 0; g < grids_.size(); ++g) {
        const FieldGrid& grid = grids_[g];
        const bool cyl = grid.kind == FieldGrid::Kind::Cylindrical;
        const std::vector<hsize_t> cells = frame_shape(grid, false);
        const std::vector<hsize_t> nodes{cells[0] + 1, cells[1] + 1, cells[2] + 1};
        x << "  <Grid Name=\"" << grid.name
          << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
        for (std::size_t k = 0; k < frames_[g].size(); ++k) {
            x << "   <Grid Name=\"" << grid.name << "_" << k << "\" GridType=\"Uniform\">\n"
              << "    <Time Value=\"" << frames_[g][k].second << "\"/>\n";
            if (cyl) {
                x << "    <Topology TopologyType=\"3DSMesh\" Dimensions=\"" << dims_text(nodes)
                  << "\"/>\n    <Geometry GeometryType=\"XYZ\">\n"
                  << "     <DataItem Dimensions=\"" << dims_text(nodes) << " 3\" NumberType=\"Float\" "
                  << "Precision=\"8\" Format=\"HDF\">" << stem_ << ".h5:/fields/" << grid.name
                  << "/nodes</DataItem>\n    </Geometry>\n";
            } else {
                const Vec3 h{(grid.hi.x - grid.lo.x) / grid.n.x, (grid.hi.y - grid.lo.y) / grid.n.y,
                             (grid.hi.z - grid.lo.z) / grid.n.z};
                x << "    <Topology TopologyType=\"3DCoRectMesh\" Dimensions=\"" << dims_text(nodes)
                  << "\"/>\n    <Geometry GeometryType=\"ORIGIN_DXDYDZ\">\n"
                  << "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
                  << "Format=\"XML\">" << grid.lo.z << " " << grid.lo.y << " " << grid.lo.x
                  << "</DataItem>\n"
                  << "     <DataItem Dimensions=\"3\" NumberType=\"Float\" Precision=\"8\" "
                  << "Format=\"XML\">" << h.z << " " << h.y << " " << h.x << "</DataItem>\n"
                  << "    </Geometry>\n";
            }
            for (const char* q : kQuantities) {
                const bool vector = std::string(q) == "velocity";
                std::vector<hsize_t> dims = frame_shape(grid, vector);
                x << "    <Attribute Name=\"" << q << "\" AttributeType=\""
                  << (vector ? "Vector" : "Scalar") << "\" Center=\"Cell\">\n"
                  << "     <DataItem Dimensions=\"" << dims_text(dims)
                  << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << stem_ << ".h5:/fields/"
                  << grid.name << "/" << q << "/frames/" << frame_name(k)
                  << "</DataItem>\n    </Attribute>\n";
            }
            x << "   </Grid>\n";
        }
        x << "  </Grid>\n";
    }
    x << " </Domain>\n</Xdmf>\n";
    write_atomically(dir_ + "/" + stem_ + ".xmf", x.str());
}

}  // namespace emergent::io
