// SPDX-License-Identifier: MIT
// Checkpoint writing and restoring.
#include "io/checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <utility>

#include "decomposition/distributor.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/build_info.hpp"
#include "emergent/error.hpp"
#include "io/h5.hpp"
#include "io/id_order.hpp"

namespace emergent::io {

namespace {
constexpr const char* kFormat = "emergent-checkpoint-1";
constexpr int kSeriesColumns = 11;

/// Names of a group's members, in name order.
std::vector<std::string> member_names(hid_t group) {
    H5G_info_t info;
    H5Gget_info(group, &info);
    std::vector<std::string> names;
    for (hsize_t k = 0; k < info.nlinks; ++k) {
        char name[256];
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name, H5P_DEFAULT);
        names.emplace_back(name);
    }
    return names;
}

/// The box as numbers: lo, hi, periodic flags, wedge images.
std::vector<double> box_record(const Box& b) {
    return {b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, double(b.periodic[0]),
            double(b.periodic[1]), double(b.periodic[2]), double(b.wedge.n)};
}

std::vector<double> pack_series(const std::vector<ThermoSample>& series) {
    std::vector<double> rows;
    for (const ThermoSample& t : series)
        rows.insert(rows.end(), {static_cast<double>(t.step), t.time, static_cast<double>(t.n),
                                 t.kinetic, t.potential, t.total, t.temperature, t.pressure,
                                 t.momentum.x, t.momentum.y, t.momentum.z});
    return rows;
}
}  // namespace

namespace {
void write_contents(hid_t file, Simulation& sim, const Config& config,
                    const std::vector<ThermoSample>& series,
                    const std::vector<FieldAccumulator>& fields, const Measures& scene_state) {
    MPI_Comm comm = sim.comm();
    {
        H5Id root = create_group(file, "checkpoint");
        write_attribute(root, "format", std::string(kFormat));
        write_attribute(root, "scene", config.scene());
        write_attribute(root, "step", sim.step_index());
        write_attribute(root, "time", sim.time());
        write_attribute(root, "rebuilds", sim.rebuilds());
        write_attribute(root, "n_global", sim.n_global());
        write_attribute(root, "ranks", static_cast<long long>(sim.n_ranks()));
        write_attribute(root, "emergent_version", std::string(build::version));
        write_attribute(root, "git_commit", std::string(build::git_commit));
        {
            H5Id params = create_group(root, "config");
            for (const auto& [key, value] : config.values()) write_attribute(params, key, value);
        }
        const std::vector<double> rows = pack_series(series);
        write_small_dataset(root, "series", H5T_NATIVE_DOUBLE,
                            {series.size(), static_cast<hsize_t>(kSeriesColumns)}, rows.data(),
                            comm);
        const std::vector<double> box = box_record(sim.box());
        write_small_dataset(root, "box", H5T_NATIVE_DOUBLE, {box.size()}, box.data(), comm);
        // The planes between domains (moved by load balance): a continuation on the same grid
        // places them where they were.
        const Int3 dims = sim.rank_grid_dims();
        const std::vector<double> grid{double(dims.x), double(dims.y), double(dims.z)};
        write_small_dataset(root, "domain_grid", H5T_NATIVE_DOUBLE, {grid.size()}, grid.data(), comm);
        const std::vector<double> cuts = sim.domain_cuts();
        write_small_dataset(root, "domain_cuts", H5T_NATIVE_DOUBLE, {cuts.size()}, cuts.data(), comm);
        const std::vector<double> tallies = sim.exchange_tallies();
        write_small_dataset(root, "exchange_tallies", H5T_NATIVE_DOUBLE, {tallies.size()},
                            tallies.data(), comm);
        {
            H5Id group = create_group(root, "scene_state");
            for (const auto& [name, values] : scene_state)
                write_small_dataset(group, name, H5T_NATIVE_DOUBLE, {values.size()},
                                    values.data(), comm);
        }

        {
            H5Id group = create_group(root, "fields");
            for (const FieldAccumulator& acc : fields) {
                const std::vector<double> sums = acc.global_sums(comm);
                write_small_dataset(group, acc.grid().name, H5T_NATIVE_DOUBLE, {sums.size()},
                                    sums.data(), comm);
                H5Id set = H5Id(H5Dopen2(group, acc.grid().name.c_str(), H5P_DEFAULT));
                write_attribute(set, "samples", acc.samples());
            }
        }

        const ParticleStore& s = std::as_const(sim).particles();
        const IdOrder order(comm, s.id.data(), s.n_owned(), sim.n_global());
        auto put = [&](const char* name, hid_t type, int width, const void* field,
                       std::size_t bytes) {
            const std::vector<char> block = order.gather(field, bytes);
            write_rows(root, name, type, sim.n_global(), width, block.data(), order.first(),
                       order.count());
        };
        put("position", H5T_NATIVE_DOUBLE, 3, s.position.data(), sizeof(Vec3));
        put("velocity", H5T_NATIVE_DOUBLE, 3, s.velocity.data(), sizeof(Vec3));
        put("force", H5T_NATIVE_DOUBLE, 3, s.force.data(), sizeof(Vec3));
        put("image", H5T_NATIVE_INT, 3, s.image.data(), sizeof(Int3));
        put("species", H5T_NATIVE_INT, 0, s.species.data(), sizeof(int));
        const std::vector<Real> ones(s.has_diameters() ? 0 : s.n_owned(), 1.0);
        put("diameter", H5T_NATIVE_DOUBLE, 0, s.has_diameters() ? s.diameter.data() : ones.data(),
            sizeof(Real));
        put("reference_position", H5T_NATIVE_DOUBLE, 3, sim.list_reference_positions().data(),
            sizeof(Vec3));
        if (sim.has_bodies()) {
            put("body", H5T_NATIVE_LLONG, 0, s.body.data(), sizeof(std::int64_t));
            // Who owns what: a body stays on its rank from one list build to the next, though
            // its centre may leave the domain meanwhile, and its spheres stay with it. A
            // continuation on the same rank grid deals them back there.
            const std::vector<int> owner(s.n_owned(), sim.rank());
            put("owner_rank", H5T_NATIVE_INT, 0, owner.data(), sizeof(int));
            const ParticleStore& b = std::as_const(sim).bodies();
            H5Id group = create_group(root, "bodies");
            write_attribute(group, "n_global", sim.n_bodies_global());
            const IdOrder border(comm, b.id.data(), b.n_owned(), sim.n_bodies_global());
            auto put_body = [&](const char* name, hid_t type, int width, const void* field,
                                std::size_t bytes) {
                const std::vector<char> block = border.gather(field, bytes);
                write_rows(group, name, type, sim.n_bodies_global(), width, block.data(),
                           border.first(), border.count());
            };
            put_body("position", H5T_NATIVE_DOUBLE, 3, b.position.data(), sizeof(Vec3));
            put_body("velocity", H5T_NATIVE_DOUBLE, 3, b.velocity.data(), sizeof(Vec3));
            put_body("image", H5T_NATIVE_INT, 3, b.image.data(), sizeof(Int3));
            put_body("kind", H5T_NATIVE_INT, 0, b.species.data(), sizeof(int));
            put_body("first_particle", H5T_NATIVE_LLONG, 0, b.body.data(), sizeof(std::int64_t));
            put_body("orientation", H5T_NATIVE_DOUBLE, 4, b.orientation.data(), sizeof(Quat));
            put_body("angular_momentum", H5T_NATIVE_DOUBLE, 4, b.angular_momentum.data(),
                     sizeof(Quat));
            const std::vector<int> body_owner(b.n_owned(), sim.rank());
            put_body("owner_rank", H5T_NATIVE_INT, 0, body_owner.data(), sizeof(int));
        }
    }
}

}  // namespace

void write_checkpoint(const std::string& path, Simulation& sim, const Config& config,
                      const std::vector<ThermoSample>& series,
                      const std::vector<FieldAccumulator>& fields, const Measures& scene_state) {
    MPI_Comm comm = sim.comm();
    const std::string tmp = path + ".tmp";
    {
        errno = 0;  // a cause found afterwards is this write's
        H5Id file = create_file(tmp, comm);
        try {
            write_contents(file, sim, config, series, fields, scene_state);
            file.close_file(tmp);
        } catch (const IoError& e) {
            int rank = 0;
            MPI_Comm_rank(comm, &rank);
            discard_file(file, tmp, rank == 0);
            throw IoError("cannot write '" + tmp + "': " + e.what() + "; the last checkpoint '" +
                          path + "' is unchanged");
        }
    }
    // Every rank has closed the file; only then does it replace the previous checkpoint.
    MPI_Barrier(comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    int failed = 0;
    if (rank == 0) failed = std::rename(tmp.c_str(), path.c_str()) != 0;
    MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
    if (failed)
        throw IoError("cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno));
}

namespace {
bool finite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
// Periodic images a run can reach (one crossing per step at most; far from int overflow).
bool plausible(const Int3& n) {
    constexpr int limit = 1 << 30;
    return std::abs(n.x) < limit && std::abs(n.y) < limit && std::abs(n.z) < limit;
}

CheckpointHeader read_header(const std::string& path, MPI_Comm comm) {
    H5Id file = open_file(path, comm, false);
    if (!exists(file, "checkpoint")) throw InputError("'" + path + "' is not an emergent checkpoint");
    H5Id root = open_group(file, "checkpoint");
    if (H5Aexists(root, "format") <= 0 || read_string_attribute(root, "format") != kFormat)
        throw InputError("'" + path + "' is not an emergent checkpoint of format " + kFormat);
    CheckpointHeader h;
    h.scene = read_string_attribute(root, "scene");
    h.step = read_integer_attribute(root, "step");
    h.time = read_double_attribute(root, "time");
    h.rebuilds = read_integer_attribute(root, "rebuilds");
    h.n_global = read_integer_attribute(root, "n_global");
    h.ranks = static_cast<int>(read_integer_attribute(root, "ranks"));
    // Counts a run cannot have written: a damaged file, named before anything is sized by them.
    auto refuse = [&](const char* name, const std::string& value) {
        throw InputError("'" + path + "': checkpoint attribute '" + name + "' is " + value);
    };
    if (h.step < 0) refuse("step", std::to_string(h.step));
    if (h.rebuilds < 0) refuse("rebuilds", std::to_string(h.rebuilds));
    if (h.n_global < 0) refuse("n_global", std::to_string(h.n_global));
    if (h.ranks < 1) refuse("ranks", std::to_string(h.ranks));
    if (!std::isfinite(h.time) || h.time < 0) refuse("time", std::to_string(h.time));
    {
        H5Id params = open_group(root, "config");
        H5O_info_t info;
        H5Oget_info(params, &info);
        for (hsize_t k = 0; k < info.num_attrs; ++k) {
            char name[256];
            H5Aget_name_by_idx(params, ".", H5_INDEX_NAME, H5_ITER_INC, k, name, sizeof name,
                               H5P_DEFAULT);
            h.config[name] = read_string_attribute(params, name);
        }
    }
    if (exists(root, "box")) h.box = read_doubles(root, "box");
    if (exists(root, "domain_grid")) {
        h.domain_grid = read_doubles(root, "domain_grid");
        h.domain_cuts = read_doubles(root, "domain_cuts");
    }
    if (exists(root, "exchange_tallies")) h.exchange_tallies = read_doubles(root, "exchange_tallies");
    // Every saved number is finite: the guards stop a run before a non-finite state is saved.
    auto finite_all = [&](const std::string& what, const std::vector<double>& values) {
        for (double x : values)
            if (!std::isfinite(x)) throw InputError("'" + path + "': " + what + " holds a non-finite value");
    };
    finite_all("exchange_tallies", h.exchange_tallies);
    const std::vector<double> rows = read_doubles(root, "series");
    if (rows.size() % kSeriesColumns != 0)
        throw InputError("'" + path + "': series is not rows of " + std::to_string(kSeriesColumns));
    finite_all("series", rows);
    for (std::size_t k = 0; k < rows.size() / kSeriesColumns; ++k) {
        const double* r = &rows[k * kSeriesColumns];
        ThermoSample t;
        t.step = static_cast<long long>(r[0]);
        t.time = r[1];
        t.n = static_cast<long long>(r[2]);
        t.kinetic = r[3], t.potential = r[4], t.total = r[5], t.temperature = r[6];
        t.pressure = r[7], t.momentum = {r[8], r[9], r[10]};
        h.series.push_back(t);
    }
    if (exists(root, "scene_state")) {
        H5Id group = open_group(root, "scene_state");
        for (const std::string& name : member_names(group))
            finite_all("scene_state '" + name + "'", h.scene_state[name] = read_doubles(group, name));
    }
    if (exists(root, "fields")) {
        H5Id group = open_group(root, "fields");
        for (const std::string& name : member_names(group)) {
            H5Id set(h5_check(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "checkpoint field"));
            h.fields[name] = {read_doubles(group, name), read_integer_attribute(set, "samples")};
            finite_all("field '" + name + "'", h.fields[name].first);
            if (h.fields[name].second < 0)
                throw InputError("'" + path + "': field '" + name + "' has " +
                                 std::to_string(h.fields[name].second) + " samples");
        }
    }
    return h;
}

void restore_particles(const std::string& path, Simulation& sim, const CheckpointHeader& h) {
    MPI_Comm comm = sim.comm();
    int rank = 0, n_ranks = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    // The scene has built its box from the run's parameters: it must be the checkpoint's
    // (checkpoints from before the box was kept skip this).
    if (!h.box.empty() && h.box != box_record(sim.box()))
        throw InputError("'" + path + "': the scene's box differs from the checkpoint's (was it "
                         "written by another version of the scene?)");
    // On the grid that wrote it, the domains are the checkpoint's; on another, equal slabs
    // (load balance, if on, moves them at its next step).
    const Int3 dims = sim.rank_grid_dims();
    const bool same_grid = h.domain_grid == std::vector<double>{double(dims.x), double(dims.y), double(dims.z)};
    if (same_grid) sim.set_domain_cuts(h.domain_cuts);
    const decomp::IdBlocks blocks{h.n_global, n_ranks};
    const long long first = blocks.first(rank);
    const auto count = static_cast<std::size_t>(blocks.first(rank + 1) - first);
    std::vector<Vec3> x(count), v(count), ref(count), f(count);
    bool with_forces = false;
    std::vector<Int3> image(count);
    std::vector<int> species(count);
    std::vector<Real> diameter(count);
    std::vector<std::int64_t> body(count, -1);
    // On the grid that wrote it, bodies and their spheres go back to the ranks that owned them
    // (checkpoints before owners were kept, and other grids: the rank holding the centre).
    std::vector<int> owner;
    std::vector<int> body_rank;  // otherwise: each body's rank by its centre, by body id
    // A damaged owner or body id seen on one rank stops every rank (no rank waits in an exchange).
    std::string damaged;
    auto agree = [&] {
        const std::string message = decomp::first_message(comm, damaged);
        if (!message.empty()) throw InputError(message);
    };
    auto check_ranks = [&](const char* name, const std::vector<int>& ranks) {
        for (int r : ranks)
            if ((r < 0 || r >= n_ranks) && damaged.empty())
                damaged = "'" + path + "': " + name + " " + std::to_string(r) + " is not a rank of this run";
    };
    ParticleStore bodies;
    bool with_bodies = false;
    long long n_bodies = 0;
    std::vector<std::int64_t> id(count);
    {
        H5Id file = open_file(path, comm, false);
        H5Id root = open_group(file, "checkpoint");
        read_rows(root, "position", H5T_NATIVE_DOUBLE, 3, x.data(), first, count, h.n_global);
        read_rows(root, "velocity", H5T_NATIVE_DOUBLE, 3, v.data(), first, count, h.n_global);
        with_forces = exists(root, "force");  // checkpoints before forces were kept: recomputed
        if (with_forces) read_rows(root, "force", H5T_NATIVE_DOUBLE, 3, f.data(), first, count, h.n_global);
        read_rows(root, "reference_position", H5T_NATIVE_DOUBLE, 3, ref.data(), first, count, h.n_global);
        read_rows(root, "image", H5T_NATIVE_INT, 3, image.data(), first, count, h.n_global);
        read_rows(root, "species", H5T_NATIVE_INT, 0, species.data(), first, count, h.n_global);
        read_rows(root, "diameter", H5T_NATIVE_DOUBLE, 0, diameter.data(), first, count, h.n_global);
        with_bodies = exists(root, "bodies");
        if (with_bodies != sim.has_bodies())
            throw InputError("checkpoint and scene disagree about rigid bodies");
        if (with_bodies) {
            read_rows(root, "body", H5T_NATIVE_LLONG, 0, body.data(), first, count, h.n_global);
            if (same_grid && exists(root, "owner_rank")) {
                owner.resize(count);
                read_rows(root, "owner_rank", H5T_NATIVE_INT, 0, owner.data(), first, count, h.n_global);
                check_ranks("owner_rank", owner);
            }
            H5Id group = open_group(root, "bodies");
            const long long nb = read_integer_attribute(group, "n_global");
            if (nb < 0) throw InputError("'" + path + "': checkpoint attribute 'bodies/n_global' is " + std::to_string(nb));
            n_bodies = nb;
            const decomp::IdBlocks bblocks{nb, n_ranks};
            const long long bfirst = bblocks.first(rank);
            const auto bcount = static_cast<std::size_t>(bblocks.first(rank + 1) - bfirst);
            std::vector<Vec3> bx(bcount), bv(bcount);
            std::vector<Int3> bimage(bcount);
            std::vector<int> kind(bcount);
            std::vector<std::int64_t> first_particle(bcount), bid(bcount);
            std::vector<Quat> q(bcount), p(bcount);
            if (!owner.empty()) read_rows(group, "position", H5T_NATIVE_DOUBLE, 3, bx.data(), bfirst, bcount, nb);
            read_rows(group, "velocity", H5T_NATIVE_DOUBLE, 3, bv.data(), bfirst, bcount, nb);
            read_rows(group, "image", H5T_NATIVE_INT, 3, bimage.data(), bfirst, bcount, nb);
            read_rows(group, "kind", H5T_NATIVE_INT, 0, kind.data(), bfirst, bcount, nb);
            read_rows(group, "first_particle", H5T_NATIVE_LLONG, 0, first_particle.data(), bfirst, bcount, nb);
            read_rows(group, "orientation", H5T_NATIVE_DOUBLE, 4, q.data(), bfirst, bcount, nb);
            read_rows(group, "angular_momentum", H5T_NATIVE_DOUBLE, 4, p.data(), bfirst, bcount, nb);
            for (std::size_t k = 0; k < bcount; ++k) bid[k] = bfirst + static_cast<long long>(k);
            for (std::size_t k = 0; k < bcount && damaged.empty(); ++k) {
                const std::string who = "'" + path + "': body " + std::to_string(bid[k]);
                const double norm2 = q[k].w * q[k].w + q[k].x * q[k].x + q[k].y * q[k].y + q[k].z * q[k].z;
                if (!finite(bx[k]) && !owner.empty()) damaged = who + " has a non-finite position";
                else if (!finite(bv[k])) damaged = who + " has a non-finite velocity";
                else if (!plausible(bimage[k])) damaged = who + " has an image beyond any run's";
                // NO_SQUISH keeps |q| = 1 to round-off (~1e-12 after 1e9 steps).
                else if (!(std::abs(norm2 - 1) < 1e-6)) damaged = who + " has an orientation that is not a unit quaternion";
                else if (!std::isfinite(p[k].w + p[k].x + p[k].y + p[k].z)) damaged = who + " has a non-finite angular_momentum";
            }
            std::vector<int> bdest(bcount);
            if (!owner.empty()) {
                read_rows(group, "owner_rank", H5T_NATIVE_INT, 0, bdest.data(), bfirst, bcount, nb);
                check_ranks("bodies/owner_rank", bdest);
            } else {
                // Bodies go to the rank holding their centre of mass, and their spheres with
                // them (so each sphere finds its saved force there): every rank reads where
                // every body goes.
                std::vector<Vec3> centre(static_cast<std::size_t>(nb));
                read_rows(group, "position", H5T_NATIVE_DOUBLE, 3, centre.data(), 0, centre.size(), nb);
                for (std::size_t b = 0; b < centre.size() && damaged.empty(); ++b)
                    if (!finite(centre[b]))
                        damaged = "'" + path + "': body " + std::to_string(b) + " has a non-finite position";
                std::copy_n(centre.begin() + bfirst, bcount, bx.begin());
                body_rank.resize(centre.size());
                for (std::size_t b = 0; b < centre.size(); ++b) body_rank[b] = sim.rank_of(centre[b]);
                for (std::size_t k = 0; k < bcount; ++k) bdest[k] = body_rank[bfirst + k];
            }
            agree();
            const decomp::Distributor bplan(comm, bdest);
            const auto mx = bplan.apply(bx), mv = bplan.apply(bv);
            const auto mimage = bplan.apply(bimage);
            const auto mkind = bplan.apply(kind);
            const auto mfirst = bplan.apply(first_particle), mid = bplan.apply(bid);
            const auto mq = bplan.apply(q), mp = bplan.apply(p);
            bodies.enable_rigid_fields();
            for (std::size_t k = 0; k < bplan.n_import(); ++k) {
                bodies.add_owned(mx[k], mv[k], mkind[k], mid[k]);
                bodies.image[k] = mimage[k];
                bodies.body[k] = mfirst[k];
                bodies.orientation[k] = mq[k];
                bodies.angular_momentum[k] = mp[k];
            }
        }
    }
    for (std::size_t k = 0; k < count; ++k) id[k] = first + static_cast<long long>(k);
    // Values no run writes (the guards stop a run before a non-finite state is saved).
    const int n_species = static_cast<int>(sim.species_masses().size());
    for (std::size_t k = 0; k < count && damaged.empty(); ++k) {
        const std::string who = "'" + path + "': particle " + std::to_string(id[k]);
        if (!finite(x[k])) damaged = who + " has a non-finite position";
        else if (!finite(v[k])) damaged = who + " has a non-finite velocity";
        else if (!finite(f[k])) damaged = who + " has a non-finite force";
        else if (!finite(ref[k])) damaged = who + " has a non-finite reference_position";
        else if (!plausible(image[k])) damaged = who + " has an image beyond any run's (" + std::to_string(image[k].x) +
                                                 ", " + std::to_string(image[k].y) + ", " + std::to_string(image[k].z) + ")";
        else if (species[k] < 0 || species[k] >= n_species)
            damaged = who + " has species " + std::to_string(species[k]) + ", which the scene does not declare";
        else if (!std::isfinite(diameter[k]) || diameter[k] < 0)
            damaged = who + " has diameter " + std::to_string(diameter[k]);
    }
    // Each particle goes to the rank whose domain held it when the list was last built (a
    // body's sphere: to its body's owner).
    std::vector<int> destination(count);
    for (std::size_t k = 0; k < count; ++k) {
        if (body[k] < -1 || body[k] >= n_bodies) {
            if (damaged.empty())
                damaged = "'" + path + "': particle " + std::to_string(first + static_cast<long long>(k)) +
                          " names body " + std::to_string(body[k]) + ", which the checkpoint lacks";
            continue;
        }
        destination[k] = !owner.empty() ? owner[k]
                         : body[k] >= 0 ? body_rank[static_cast<std::size_t>(body[k])]
                                        : sim.rank_of(ref[k]);
    }
    agree();
    const decomp::Distributor plan(comm, destination);
    const auto mx = plan.apply(x), mv = plan.apply(v), mref = plan.apply(ref), mf = plan.apply(f);
    const auto mimage = plan.apply(image);
    const auto mspecies = plan.apply(species);
    const auto mdiameter = plan.apply(diameter);
    const auto mid = plan.apply(id);
    const auto mbody = plan.apply(body);
    ParticleStore owned;
    if (with_bodies) owned.enable_rigid_fields();
    for (std::size_t k = 0; k < plan.n_import(); ++k) {
        owned.add_owned(mx[k], mv[k], mspecies[k], mid[k], mdiameter[k]);
        owned.image[k] = mimage[k];
        owned.force[k] = mf[k];
        if (with_bodies) owned.body[k] = mbody[k];
    }
    try {
        sim.restore(std::move(owned), std::vector<Vec3>(mref.begin(), mref.end()), h.step, h.time,
                    h.rebuilds, with_bodies ? &bodies : nullptr, with_forces);
    } catch (const InputError& e) {
        throw InputError("'" + path + "': " + e.what());
    }
}

}  // namespace

// A checkpoint that opens but fails to read is damaged input, not a failing disk of this run.
CheckpointHeader read_checkpoint_header(const std::string& path, MPI_Comm comm) {
    try {
        return read_header(path, comm);
    } catch (const IoError& e) {
        throw InputError("'" + path + "' is a damaged checkpoint (" + e.what() + ")");
    }
}

void restore_checkpoint(const std::string& path, Simulation& sim, const CheckpointHeader& h) {
    try {
        restore_particles(path, sim, h);
    } catch (const IoError& e) {
        throw InputError("'" + path + "' is a damaged checkpoint (" + e.what() + ")");
    }
}

}  // namespace emergent::io
