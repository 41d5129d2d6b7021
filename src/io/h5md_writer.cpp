// SPDX-License-Identifier: MIT
// H5MD trajectory writer.
#include "io/h5md_writer.hpp"

#include <algorithm>
#include <cstring>

#include "emergent/build_info.hpp"
#include "emergent/error.hpp"
#include "io/id_order.hpp"

namespace emergent::io {

const std::vector<std::string>& H5mdWriter::known_elements() {
    static const std::vector<std::string> names{"position", "velocity", "species", "id", "image"};
    return names;
}

H5mdWriter::H5mdWriter(const std::string& path, MPI_Comm comm, const H5mdMetadata& meta)
    : comm_(comm), meta_(meta) {
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
    H5Id all = create_group(particles_, "all");
    {
        H5Id box = create_group(all, "box");
        write_attribute(box, "dimension", 3LL);
        std::vector<std::string> boundary;
        for (int d = 0; d < 3; ++d) boundary.push_back(meta.box.periodic[d] ? "periodic" : "none");
        write_attribute(box, "boundary", boundary);
        // Edges as a time-dependent element of 3x3 box vectors (the rectangular case of the
        // triclinic form): valid H5MD, and what MDAnalysis's H5MD reader expects.
        series_["box/edges"] = std::make_unique<TimeSeries>(box, "edges", H5T_NATIVE_DOUBLE,
                                                            std::vector<hsize_t>{3, 3});
        // Where the box starts (H5MD assumes the origin; our boxes may start elsewhere).
        const double lower[3] = {meta.box.lo.x, meta.box.lo.y, meta.box.lo.z};
        write_small_dataset(box, "offset", H5T_NATIVE_DOUBLE, {3}, lower, comm);
    }
    const auto n = static_cast<hsize_t>(meta.n_global);
    for (const std::string& e : meta.elements) {
        if (e == "position" || e == "velocity")
            series_["p/" + e] = std::make_unique<TimeSeries>(all, e, H5T_NATIVE_DOUBLE,
                                                             std::vector<hsize_t>{n, 3});
        else if (e == "image")
            series_["p/" + e] = std::make_unique<TimeSeries>(all, e, H5T_NATIVE_INT,
                                                             std::vector<hsize_t>{n, 3});
        else if (e == "species")
            series_["p/" + e] = std::make_unique<TimeSeries>(all, e, H5T_NATIVE_INT,
                                                             std::vector<hsize_t>{n});
        else if (e == "id")
            series_["p/" + e] = std::make_unique<TimeSeries>(all, e, H5T_NATIVE_LLONG,
                                                             std::vector<hsize_t>{n});
        else
            throw InputError("output.elements: unknown element '" + e +
                             "' (known: position, velocity, species, id, image)");
    }
    observables_ = create_group(file_, "observables");
}

H5mdWriter::~H5mdWriter() = default;

void H5mdWriter::write_particles(ParticleStore& store, long long step, double time) {
    const IdOrder order(comm_, store.id.data(), store.n_owned(), meta_.n_global);
    auto write = [&](const std::string& name, const void* field, std::size_t bytes) {
        const std::vector<char> rows = order.gather(field, bytes);
        series_.at("p/" + name)->append(step, time, rows.data(), order.first(), order.count(),
                                        comm_);
    };
    const Vec3 len = meta_.box.length();
    const double edges[9] = {len.x, 0, 0, 0, len.y, 0, 0, 0, len.z};
    int rank = 0;
    MPI_Comm_rank(comm_, &rank);
    series_.at("box/edges")->append(step, time, edges, 0, rank == 0 ? 3 : 0, comm_);
    for (const std::string& e : meta_.elements) {
        if (e == "position") write(e, store.position.data(), sizeof(Vec3));
        if (e == "velocity") write(e, store.velocity.data(), sizeof(Vec3));
        if (e == "species") write(e, store.species.data(), sizeof(int));
        if (e == "id") write(e, store.id.data(), sizeof(std::int64_t));
        if (e == "image") write(e, store.image.data(), sizeof(Int3));
    }
    H5Fflush(file_, H5F_SCOPE_GLOBAL);
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

void H5mdWriter::finish() {
    if (file_ < 0) return;
    H5Id h5md = open_group(file_, "h5md");
    write_attribute(h5md, "emergent_complete", 1LL);
    h5md.reset();
    series_.clear();
    observables_.reset();
    particles_.reset();
    file_.reset();
}

}  // namespace emergent::io
