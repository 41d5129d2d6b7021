// SPDX-License-Identifier: MIT
// H5MD trajectory writer.
#include "io/h5md_writer.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "emergent/build_info.hpp"
#include "emergent/error.hpp"
#include "io/atomic_file.hpp"
#include "io/id_order.hpp"

namespace emergent::io {

const std::vector<std::string>& H5mdWriter::known_elements() {
    static const std::vector<std::string> names{"position", "velocity", "species", "id", "image", "diameter"};
    return names;
}

H5mdWriter::H5mdWriter(const std::string& path, MPI_Comm comm, const H5mdMetadata& meta)
    : comm_(comm), meta_(meta) {
    // The XDMF sidecar sits beside the file: DIR/STEM.h5 -> DIR/STEM.xmf.
    file_name_ = std::filesystem::path(path).filename().string();
    sidecar_ = std::filesystem::path(path).replace_extension().string();
    int n_ranks = 1;
    MPI_Comm_size(comm, &n_ranks);
    file_ = create_file(path, comm);
    {
        H5Id h5md = create_group(file_, "h5md");
        write_attribute(h5md, "version", std::vector<int>{1, 1});
        write_attribute(h5md, "emergent_complete", 0LL);
        H5Id author = create_group(h5md, "author");
        write_attribute(author, "name", std::string("emergent user"));
        H5Id creator = create_group(h5md, "creator");
        write_attribute(creator, "name", std::string("emergent"));
        write_attribute(creator, "version", std::string(build::version));
    }
    {
        H5Id params = create_group(file_, "parameters");
        write_attribute(params, "scene", meta.config->scene());
        for (const auto& [key, value] : meta.config->values()) write_attribute(params, key, value);
        H5Id build_group = create_group(params, "build");
        write_attribute(build_group, "version", std::string(build::version));
        write_attribute(build_group, "git_commit", std::string(build::git_commit));
        write_attribute(build_group, "ranks", static_cast<long long>(n_ranks));
    }
    particles_ = create_group(file_, "particles");
    add_group("all", "p/", meta.n_global, meta.elements);
    if (meta.n_bodies > 0)
        add_group("bodies", "b/", meta.n_bodies,
                  {"position", "velocity", "orientation", "image", "species", "id"});
    observables_ = create_group(file_, "observables");
}

void H5mdWriter::add_group(const std::string& name, const std::string& key, long long n_global,
                           const std::vector<std::string>& elements) {
    H5Id group = create_group(particles_, name);
    {
        H5Id box = create_group(group, "box");
        write_attribute(box, "dimension", 3LL);
        std::vector<std::string> boundary;
        for (int d = 0; d < 3; ++d) boundary.push_back(meta_.box.periodic[d] ? "periodic" : "none");
        write_attribute(box, "boundary", boundary);
        // Edges as a time-dependent element of 3x3 box vectors (the rectangular case of the
        // triclinic form): valid H5MD, and what MDAnalysis's H5MD reader expects.
        series_[key + "box/edges"] = std::make_unique<TimeSeries>(box, "edges", H5T_NATIVE_DOUBLE,
                                                                  std::vector<hsize_t>{3, 3});
        // Where the box starts (H5MD assumes the origin; our boxes may start elsewhere).
        const double lower[3] = {meta_.box.lo.x, meta_.box.lo.y, meta_.box.lo.z};
        write_small_dataset(box, "offset", H5T_NATIVE_DOUBLE, {3}, lower, comm_);
    }
    const auto n = static_cast<hsize_t>(n_global);
    for (const std::string& e : elements) {
        hid_t type = H5T_NATIVE_DOUBLE;
        std::vector<hsize_t> frame{n, 3};
        if (e == "orientation") frame = {n, 4};  // unit quaternion, scalar first (w, x, y, z)
        if (e == "image") type = H5T_NATIVE_INT;
        if (e == "species") type = H5T_NATIVE_INT, frame = {n};
        if (e == "id") type = H5T_NATIVE_LLONG, frame = {n};
        if (e == "diameter") frame = {n};
        series_[key + e] = std::make_unique<TimeSeries>(group, e, type, frame);
    }
    H5Id frames = create_group(group, "frames");
    for (const std::string& e : elements) create_group(frames, e);
    groups_[key] = Shown{name, n_global, elements, {}};
}

void H5mdWriter::write_group(const std::string& key, const ParticleStore& store, long long n_global,
                             const std::vector<std::string>& elements, long long step, double time,
                             const Measures& extra) {
    const IdOrder order(comm_, store.id.data(), store.n_owned(), n_global);
    auto write = [&](const std::string& name, const void* field, std::size_t bytes) {
        const std::vector<char> rows = order.gather(field, bytes);
        series_.at(key + name)->append(step, time, rows.data(), order.first(), order.count(), comm_);
    };
    const Vec3 len = meta_.box.length();
    const double edges[9] = {len.x, 0, 0, 0, len.y, 0, 0, 0, len.z};
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    series_.at(key + "box/edges")->append(step, time, edges, 0, rank == 0 ? 3 : 0, comm_);
    for (const std::string& e : elements) {
        if (e == "position") write(e, store.position.data(), sizeof(Vec3));
        if (e == "velocity") write(e, store.velocity.data(), sizeof(Vec3));
        if (e == "orientation") write(e, store.orientation.data(), sizeof(Quat));
        if (e == "species") write(e, store.species.data(), sizeof(int));
        if (e == "id") write(e, store.id.data(), sizeof(std::int64_t));
        if (e == "image") write(e, store.image.data(), sizeof(Int3));
        if (e == "diameter") {
            const std::vector<Real> ones(store.has_diameters() ? 0 : store.n_owned(), 1.0);
            write(e, store.has_diameters() ? store.diameter.data() : ones.data(), sizeof(Real));
        }
    }
    Shown& shown = groups_.at(key);
    for (const auto& [name, values] : extra) {
        if (values.size() != store.n_owned())
            throw std::logic_error("trajectory: per-body values '" + name + "' do not match the bodies");
        if (!series_.count(key + name)) {  // a new element at its first frame
            H5Id group = open_group(particles_, shown.name);
            series_[key + name] = std::make_unique<TimeSeries>(group, name, H5T_NATIVE_DOUBLE,
                                                               std::vector<hsize_t>{static_cast<hsize_t>(n_global)});
            H5Id frames = open_group(group, "frames");
            create_group(frames, name);
            shown.elements.push_back(name);
        }
        write(name, values.data(), sizeof(double));
    }
    // What a viewer reads: each element's frame as a dataset of its own (a view, no copy), and
    // once the particles' connectivity (0..N-1), which ParaView's XDMF3 readers need to show
    // points. Then the sidecar names them all.
    const std::string root = "/particles/" + shown.name;
    if (shown.times.empty()) {
        std::vector<std::int64_t> ids(order.count());
        for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = order.first() + static_cast<long long>(i);
        H5Id group = open_group(particles_, shown.name);
        write_rows(group, "connectivity", H5T_NATIVE_LLONG, n_global, 0, ids.data(), order.first(), ids.size());
    }
    const hsize_t k = shown.times.size();
    H5Id frames = open_group(particles_, shown.name + "/frames");
    for (const std::string& e : shown.elements) {
        const TimeSeries& series = *series_.at(key + e);
        H5Id group = open_group(frames, e);
        add_frame_view(group, frame_name(k), series.value(), root + "/" + e + "/value", k, series.type());
    }
    shown.times.push_back(time);
    write_sidecar();
}

void H5mdWriter::write_sidecar() const {
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    if (rank != 0) return;
    // One sidecar per group: ParaView's Xdmf3ReaderS merges the grids of one file into a single
    // point set, which would mix spheres and bodies.
    for (const auto& [key, shown] : groups_) {
        if (shown.times.empty()) continue;
        std::ostringstream x;
        x.precision(17);
        x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
          << "<Xdmf Version=\"2.0\">\n <Domain>\n";
        const std::string n = std::to_string(shown.n_global);
        const std::string root = file_name_ + ":/particles/" + shown.name;
        x << "  <Grid Name=\"" << shown.name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
        for (std::size_t k = 0; k < shown.times.size(); ++k) {
            const std::string frame = frame_name(k);
            x << "   <Grid Name=\"" << shown.name << "_" << frame << "\" GridType=\"Uniform\">\n"
              << "    <Time Value=\"" << shown.times[k] << "\"/>\n"
              << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
              << "\" NodesPerElement=\"1\">\n     <DataItem Dimensions=\"" << n
              << "\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" << root
              << "/connectivity</DataItem>\n    </Topology>\n";
            for (const std::string& e : shown.elements) {
                // XDMF's element types: what each H5MD element holds.
                const bool vec = e == "position" || e == "velocity" || e == "image";
                const bool quat = e == "orientation";
                const bool int4 = e == "species" || e == "image";
                const std::string dims = n + (vec ? " 3" : quat ? " 4" : "");
                const std::string item = "     <DataItem Dimensions=\"" + dims + "\" NumberType=\"" +
                                         (int4 || e == "id" ? "Int" : "Float") + "\" Precision=\"" +
                                         (int4 ? "4" : "8") + "\" Format=\"HDF\">" + root + "/frames/" + e +
                                         "/" + frame + "</DataItem>\n";
                if (e == "position") {
                    x << "    <Geometry GeometryType=\"XYZ\">\n" << item << "    </Geometry>\n";
                } else {
                    x << "    <Attribute Name=\"" << e << "\" AttributeType=\""
                      << (vec ? "Vector" : quat ? "Matrix" : "Scalar") << "\" Center=\"Node\">\n"
                      << item << "    </Attribute>\n";
                }
            }
            x << "   </Grid>\n";
        }
        x << "  </Grid>\n </Domain>\n</Xdmf>\n";
        write_atomically(sidecar_ + (shown.name == "all" ? "" : "." + shown.name) + ".xmf", x.str());
    }
}

H5mdWriter::~H5mdWriter() = default;

void H5mdWriter::write_particles(const ParticleStore& store, long long step, double time) {
    write_group("p/", store, meta_.n_global, meta_.elements, step, time);
    flush();
}

void H5mdWriter::write_bodies(const ParticleStore& bodies, long long step, double time, const Measures& extra) {
    write_group("b/", bodies, meta_.n_bodies,
                {"position", "velocity", "orientation", "image", "species", "id"}, step, time, extra);
}

void H5mdWriter::write_observable(const std::string& name, long long step, double time,
                                  const std::vector<double>& value) {
    auto& series = series_["o/" + name];
    if (!series) {
        std::vector<hsize_t> frame;
        if (value.size() > 1) frame.push_back(value.size());
        series = std::make_unique<TimeSeries>(observables_, name, H5T_NATIVE_DOUBLE, frame);
    }
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    const hsize_t rows = rank == 0 ? (value.size() > 1 ? value.size() : 1) : 0;
    series->append(step, time, value.data(), 0, rows, comm_);
}

void H5mdWriter::flush() { h5_check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush"); }

void H5mdWriter::finish() {
    if (file_ < 0) return;
    H5Id h5md = open_group(file_, "h5md");
    write_attribute(h5md, "emergent_complete", 1LL);
    h5md.reset();
    series_.clear();
    observables_.reset();
    particles_.reset();
    file_.close_file(sidecar_ + ".h5");  // a run whose last writes failed does not end well
}

}  // namespace emergent::io
