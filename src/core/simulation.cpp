// SPDX-License-Identifier: MIT
// The time step and the parts it is made of.
#include "emergent/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "decomposition/exact_sum.hpp"
#include "decomposition/halo_exchange.hpp"
#include "decomposition/load_balance.hpp"
#include "decomposition/migration.hpp"
#include "decomposition/rank_grid.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "emergent/gpu.hpp"
#include "emergent/random.hpp"
#include "neighbour/backend_halo.hpp"
#include "particles/particle_mirror.hpp"
#include "integrate/kick_drift.hpp"
#include "integrate/particle_sums.hpp"
#include "neighbour/backend_list_build.hpp"
#include "neighbour/list_build_loops.hpp"
#include "observe/field_sampling.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/neighbour_list.hpp"
#include "rigid/rigid_bodies.hpp"

namespace emergent {

namespace {
using Clock = std::chrono::steady_clock;

/// The value kept for `id` in pairs sorted by id, or null.
template <class T>
const T* find_by_id(const std::vector<std::pair<std::int64_t, T>>& sorted, std::int64_t id) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), id,
                                     [](const auto& entry, std::int64_t key) { return entry.first < key; });
    return it != sorted.end() && it->first == id ? &it->second : nullptr;
}

/// Adds the seconds since construction to `slot` when it goes out of scope.
class PhaseTimer {
public:
    /// Adds the time to `slot`, and to `*also` where given.
    explicit PhaseTimer(double& slot, double* also = nullptr) : slot_(slot), also_(also), start_(Clock::now()) {}
    ~PhaseTimer() {
        const double t = std::chrono::duration<double>(Clock::now() - start_).count();
        slot_ += t;
        if (also_) *also_ += t;
    }

private:
    double& slot_;
    double* also_;
    Clock::time_point start_;
};
}  // namespace

struct Simulation::Engine {
    MPI_Comm comm;
    RunSettings settings;
    Box box;
    std::unique_ptr<decomp::RankGrid> grid;
    ParticleStore store;
    std::vector<double> mass{1.0}, inverse_mass{1.0};
    std::vector<std::unique_ptr<ForceTerm>> forces;
    std::unique_ptr<Thermostat> thermostat;
    std::optional<BodyLangevinSettings> body_langevin;
    std::vector<std::unique_ptr<BoundaryRule>> boundaries;
    std::vector<std::unique_ptr<WallLayerThermostat>> wall_layers;
    std::string boundary_fault;  ///< first particle a rule could not return, since last check
    decomp::Migration migration;
    decomp::HaloExchange halo;
    MessageTraffic traffic_at_reset;  ///< the counters when the measured phase began
    CellList cells;
    NeighbourList list;
    ForceSums sums;
    unsigned ghost_fields = kPosition;
    unsigned particle_fields = kPosition;  ///< what the force terms read of owned particles
    long long n_global = 0, step = 0, rebuilds = 0;
    bool moved_since_build = true;  ///< a drift since the last list build
    /// Set by a restore for its one build: the saved list-reference positions by id (sorted).
    /// Bodies' spheres are binned there, where the run's last build binned them, rather than
    /// at their bodies' current poses, so the list and the force sums' order are the run's.
    std::vector<std::pair<std::int64_t, Vec3>> restored_reference;
    /// Set by a restore for its one build: the bodies were dealt to the ranks that owned them
    /// (on the rank count that wrote the state) or that hold their centres, and stay there until
    /// the run's next build, as they would have in the uninterrupted run.
    bool bodies_dealt = false;
    bool built_this_step = false;   ///< the list was rebuilt within the current step
    /// The largest squared displacement since the last build, taken in the last drift's pass
    /// (kick_drift), for the rebuild test that follows it.
    double drift_moved_sq = 0;
    bool drift_moved_known = false;
    /// This rank's free kinetic energy, summed in the last kick's pass for the thermostat.
    double kick_kinetic = 0;
    bool kick_kinetic_known = false;
    bool balance_due = false;       ///< the planes move at this step's next drift
    /// Ghost refresh overlapped with the pair forces (Simulation::halo_overlap()). Where the run
    /// allows it, the owned particles are ordered with the n_interior whose list rows need no
    /// ghost first, whether or not the overlap is switched on, so that on and off give the
    /// same bits; refresh_in_flight between a drift's start of the refresh and the forces.
    bool interior_first = false;
    std::size_t n_interior = 0;
    bool refresh_in_flight = false;
    double wait_at_reset = 0;
    LoadBalanceStats balance_stats;
    mutable std::vector<std::uint32_t> cost_scratch, offset_copy;
    double time = 0;
    PhaseTimes times;
    std::vector<std::uint32_t> order;
    rigid::RigidBodies rigid;
    /// The particle arrays in the back end's memory; null on the host back end, whose loops
    /// work on the store itself.
    std::unique_ptr<exec::ParticleMirror> mirror;
    /// Where the loops run (exec::Target): the host's loops, or CUDA kernels.
    exec::Target target;
    /// Full neighbour list, force terms in their back-end form (ListLayout).
    bool full_list = false;
    const std::uint32_t *list_offset = nullptr, *list_index = nullptr;  ///< where the back end reads it
    std::vector<Real> energy_scratch, virial_scratch, overlap_scratch;  ///< host back end's sums
    /// With a mirror, the rebuild test and the ghosts' positions run on the back end too.
    exec::BackendHalo backend_halo;
    const Vec3* reference_on_backend = nullptr;  ///< positions at the last list build
    /// List builds where the particles live (one rank without bodies), and whether the last
    /// build was one: then the host's copy of its reference positions is made on demand.
    BackendListBuild backend_build;
    bool built_on_backend = false;
    mutable bool reference_copied = false;
    mutable std::vector<Vec3> reference_copy;
    /// The rigid bodies' arrays in the back end's memory (with a mirror and bodies), and where
    /// their frames and constituent index are there.
    std::unique_ptr<exec::ParticleMirror> body_mirror;
    rigid::FrameTable frames_on_backend{};
    rigid::ConstituentIndex constituents_on_backend{};
    // The mirrors' buffers the engine fills.
    enum Upload : std::size_t { kListOffsets, kListIndex, kHaloIndex, kReference };
    enum BodyUpload : std::size_t { kFrameInertia, kFrameFirst, kFramePositions, kConstituentFirst,
                                    kConstituentIndex, kFrameSpecies, kFrameDiameters };
    /// The constituents' species and diameters by frame position, on the back end.
    const int* frame_species_on_backend = nullptr;
    const double* frame_diameters_on_backend = nullptr;
    // kHaloPack and the two after it: BackendHalo::gather's.
    enum Scratch : std::size_t { kEnergy, kVirial, kOverlap, kHaloPack, kFieldKeys = kHaloPack + 3,
                                 kFieldMembers, kFieldStart, kFieldSums };

    // Each part of the step says what it reads and writes where it runs: on the back end
    // (functors through the execution layer, on the mirror's arrays) or as host code on the
    // store (what is not converted yet, and what needs the host: decomposition, output). The
    // mirror copies a field only where its copy there is stale; on the host back end all of
    // this is nothing.
    void backend_reads(unsigned fields) const {
        if (mirror) mirror->to_backend(host_store(), fields);
    }
    void backend_wrote(unsigned fields) const {
        if (mirror) mirror->written_on_backend(host_store(), fields);
    }
    void host_reads(unsigned fields) const {
        if (mirror) mirror->to_host(host_store(), fields);
    }
    void host_wrote(unsigned fields) const {
        if (mirror) mirror->written_on_host(fields);
    }
    /// Bringing the host's copy up to date is no change of the simulation's state, so const
    /// members may sync.
    ParticleStore& host_store() const { return const_cast<ParticleStore&>(store); }
    /// Per-species masses where the back end's loops read them.
    /// The mirror's table slots: masses, inverse masses, the list's ranges by species pair.
    enum Table : std::size_t { kMassTable, kInverseMassTable, kPairRangeTable };
    const double* masses() const { return mirror ? mirror->table(kMassTable, mass) : mass.data(); }
    const double* inverse_masses() const {
        return mirror ? mirror->table(kInverseMassTable, inverse_mass) : inverse_mass.data();
    }
    /// The array of `field` the back end's loops work on.
    template <class T>
    T* data(FieldMask field, const std::vector<T>& host) const {
        return mirror ? mirror->array<T>(field) : const_cast<T*>(host.data());
    }

    bool bodies() const { return !rigid.empty_everywhere(); }

    // The bodies' fields, like the particles' (above): where the step's loops over bodies read
    // and write them. A body's kBody is the id of its first sphere (RigidBodies' append).
    static constexpr unsigned kBodyFields = kPosition | kVelocity | kForce | kSpecies | kId | kImage |
                                            kBody | kOrientation | kAngularMomentum | kTorque;
    ParticleStore& host_bodies() const { return const_cast<rigid::RigidBodies&>(rigid).store(); }
    /// The bodies' arrays where the loops run, holding the current values of `fields`.
    rigid::RigidBodies::Arrays body_arrays(unsigned fields) const {
        if (!body_mirror) return rigid.host_arrays();
        body_mirror->to_backend(host_bodies(), fields);
        rigid::RigidBodies::Arrays a;
        a.state = {body_mirror->array<Vec3>(kPosition), body_mirror->array<Vec3>(kVelocity),
                   body_mirror->array<Vec3>(kForce), body_mirror->array<Quat>(kOrientation),
                   body_mirror->array<Quat>(kAngularMomentum), body_mirror->array<Vec3>(kTorque),
                   body_mirror->array<int>(kSpecies)};
        a.frames = frames_on_backend;
        a.frames.mass = body_mirror->table(0, rigid.frame_masses());
        a.constituents = constituents_on_backend;
        a.id = body_mirror->array<std::int64_t>(kId);
        a.image = body_mirror->array<Int3>(kImage);
        return a;
    }
    void bodies_wrote(unsigned fields) const {
        if (body_mirror) body_mirror->written_on_backend(host_bodies(), fields);
    }
    void bodies_to_host(unsigned fields) const {
        if (body_mirror) body_mirror->to_host(host_bodies(), fields);
    }
    void bodies_host_wrote(unsigned fields) const {
        if (body_mirror) body_mirror->written_on_host(fields);
    }
    /// The kinds' frames where the back end reads them (once: they are fixed by initialise).
    void place_body_frames() {
        if (!body_mirror || !bodies()) return;
        auto up = [&](std::size_t slot, const auto& v) {
            using T = typename std::decay_t<decltype(v)>::value_type;
            return static_cast<const T*>(body_mirror->upload(slot, v.data(), v.size() * sizeof(T)));
        };
        frames_on_backend.inertia = up(kFrameInertia, rigid.frame_inertia());
        frames_on_backend.first = up(kFrameFirst, rigid.frame_first());
        frames_on_backend.positions = up(kFramePositions, rigid.frame_positions());
        frame_species_on_backend = up(kFrameSpecies, rigid.frame_species());
        frame_diameters_on_backend = up(kFrameDiameters, rigid.frame_diameters());
    }
    /// The constituent index where the back end reads it (after each build).
    void place_constituents() {
        if (!body_mirror || !bodies()) return;
        const auto& first = rigid.constituent_first();
        const auto& index = rigid.constituent_index();
        constituents_on_backend.first = static_cast<const std::uint32_t*>(
            body_mirror->upload(kConstituentFirst, first.data(), first.size() * sizeof(std::uint32_t)));
        constituents_on_backend.index = static_cast<const std::uint32_t*>(
            body_mirror->upload(kConstituentIndex, index.data(), index.size() * sizeof(std::uint32_t)));
    }
    /// Constituents of a body owned here may stick out of the domain by the body's extent.
    double ghost_width() const { return list.list_cutoff() + rigid.max_extent(); }

    /// Sets up the list and cells for the force terms present, and counts particles.
    void prepare() {
        require_grid("initialise");
        host_reads(kAllFields);  // the store's arrays are refitted below
        host_wrote(kAllFields);
        double cutoff = 0;
        for (const auto& term : forces) cutoff = std::max(cutoff, term->cutoff());
        list = NeighbourList(cutoff, settings.skin);
        set_pair_ranges(cutoff);
        grid->require_width(ghost_width());
        cells.setup(grid->lo(), grid->hi(), ghost_width(), list.list_cutoff(),
                    settings.cell_subdivisions);
        if (bodies() && !wall_layers.empty())
            throw InputError("wall-layer thermostats act on free particles only");
        if (bodies() && !boundaries.empty())
            throw InputError("boundary rules (hard walls) act on free particles only; rigid "
                             "bodies need force walls");
        if (bodies() && box.wedge.active())
            throw InputError("rigid bodies in a wedge region are not supported");
        n_global = decomp::sum(comm, static_cast<long long>(store.n_owned()));
        if (particle_fields & kDiameter) store.enable_diameters();  // contacts read them
        store.fit_capacity();
        choose_list_layout();
    }

    /// The terms' ranges by species pair, the largest for each pair (symmetric, at most the
    /// cutoff), set on the list where some pair's is shorter than the cutoff.
    void set_pair_ranges(double cutoff) {
        std::vector<std::vector<double>> tables;  // each term's, and its width
        std::vector<std::size_t> widths;
        std::size_t n = 0;
        for (const auto& term : forces) {
            tables.push_back(term->pair_ranges());
            const std::size_t size = tables.back().size(),
                              m = static_cast<std::size_t>(std::llround(std::sqrt(double(size))));
            if (m * m != size) throw std::logic_error("force term '" + term->name() + "': pair_ranges() is not n x n");
            widths.push_back(m);
            n = std::max(n, m);
        }
        if (n == 0) return;
        std::vector<double> range(n * n, 0.0);
        for (std::size_t t = 0; t < forces.size(); ++t) {
            const std::vector<double>& own = tables[t];
            const std::size_t m = widths[t];
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t j = 0; j < n; ++j) {
                    const double r = i < m && j < m ? std::max(own[i * m + j], own[j * m + i]) : forces[t]->cutoff();
                    range[i * n + j] = std::max(range[i * n + j], std::min(r, cutoff));
                }
        }
        if (std::all_of(range.begin(), range.end(), [&](double r) { return r >= cutoff; })) return;
        list.set_pair_ranges(range, static_cast<int>(n));
    }

    void choose_list_layout() {
        const ListLayout layout = settings.list_layout;
        std::string host_only;
        for (const auto& term : forces)
            if (!term->on_backend() && host_only.empty()) host_only = term->name();
        if (layout == ListLayout::Full && !host_only.empty())
            throw InputError("neighbour_list=full: force term '" + host_only +
                             "' has no back-end form yet (use half or auto)");
        full_list = layout == ListLayout::Full ||
                    (layout == ListLayout::Auto && settings.backend != Backend::Host && host_only.empty());
        // Wedge images and bodies' spheres may lie inside a domain as ghosts: no particle is
        // sure to be free of them, so nothing is ordered. Only for the overlap (or to check it):
        // the order takes some memory locality from the force loop and the list build, and on
        // one node the overlap gained nothing (benchmarks/RESULTS.md), so runs without it keep
        // the plain cell order.
        interior_first = !mirror && !full_list && !bodies() && !box.wedge.active() && !forces.empty() &&
                         forces.front()->cutoff() > 0 && forces.front()->honours_range() && grid->size() > 1 &&
                         (settings.overlap_halo || settings.interior_order);
        n_interior = 0;
    }

    /// The same on every rank (the refresh's messages must match), even where a rank has no
    /// interior particle.
    bool overlap_now() const { return interior_first && settings.overlap_halo; }

    /// The particles and the full list as the back end's loops see them.
    BackendParticles backend_particles() {
        BackendParticles p;
        p.position = data(kPosition, store.position);
        p.velocity = data(kVelocity, store.velocity);
        p.force = data(kForce, store.force);
        p.species = data(kSpecies, store.species);
        p.id = data(kId, store.id);
        p.target = target;
        p.diameter = store.has_diameters() ? data(kDiameter, store.diameter) : nullptr;
        p.mass = masses();
        p.n_owned = store.n_owned();
        p.size = store.size();
        p.list_offset = list_offset;
        p.list_index = list_index;
        const std::size_t bytes = p.n_owned * sizeof(Real);
        if (mirror) {
            p.energy = static_cast<Real*>(mirror->scratch(kEnergy, bytes));
            p.virial = static_cast<Real*>(mirror->scratch(kVirial, bytes));
            p.overlap = static_cast<Real*>(mirror->scratch(kOverlap, bytes));
        } else {
            energy_scratch.resize(p.n_owned);
            virial_scratch.resize(p.n_owned);
            overlap_scratch.resize(p.n_owned);
            p.energy = energy_scratch.data();
            p.virial = virial_scratch.data();
            p.overlap = overlap_scratch.data();
        }
        return p;
    }

    /// The list where the back end reads it: uploaded after each build (host code builds it).
    void place_full_list() {
        list_offset = list.offsets();
        list_index = list.neighbours();
        if (!mirror) return;
        list_offset = static_cast<const std::uint32_t*>(
            mirror->upload(kListOffsets, list.offsets(), (list.n_owned() + 1) * sizeof(std::uint32_t)));
        list_index = static_cast<const std::uint32_t*>(
            mirror->upload(kListIndex, list.neighbours(), list.n_pairs() * sizeof(std::uint32_t)));
    }

    /// Re-partitions particles and rebuilds ghosts, cells and the Verlet list.
    /// Stops every rank together if some boundary rule could not keep a particle inside.
    void agree_on_boundary_faults() {
        const std::string message = decomp::first_message(comm, boundary_fault);
        boundary_fault.clear();
        if (!message.empty()) throw InstabilityError(message);
    }

    /// Where the rebuild test's origin (the owned positions at the last build) lies in the
    /// memory the loops run on; null where it does not match the owned particles.
    const Vec3* check_origin() const {
        if (mirror) return reference_on_backend;
        const std::vector<Vec3>& x0 = list.reference_positions();
        return x0.size() == store.n_owned() ? x0.data() : nullptr;
    }

    /// Owned positions at the last list build (the displacement check's origin), on the host.
    const std::vector<Vec3>& reference_positions() const {
        if (!built_on_backend) return list.reference_positions();
        if (!reference_copied) {
            reference_copy.resize(store.n_owned());
            mirror->copy_to_host(reference_copy.data(), reference_on_backend, store.n_owned() * sizeof(Vec3));
            reference_copied = true;
        }
        return reference_copy;
    }

    /// `on_backend`: the build may run where the particles live (BackendListBuild; on one rank
    /// it moves no particle array); the host builds for the half list, at initialise and
    /// restore, and where the back end declines (ids beyond its 32-bit sort keys).
    void rebuild(bool on_backend = false) {
        PhaseTimer timer(times.neighbour);
        drift_moved_known = false;
        if (on_backend && mirror && full_list) {
            if (!boundaries.empty()) agree_on_boundary_faults();
            BackendListBuild::Bodies body_tables;
            if (bodies())
                body_tables = {&rigid,           body_mirror.get(),        &host_bodies(),
                               frames_on_backend, frame_species_on_backend, frame_diameters_on_backend,
                               kBodyFields};
            const int n_species = list.n_range_species();
            backend_build.set_pair_ranges(n_species ? mirror->table(kPairRangeTable, list.range_table()) : nullptr,
                                          n_species);
            if (backend_build.build(target, *mirror, store, *grid, cells, ghost_width(), list.list_cutoff(),
                                    halo, backend_halo, bodies() ? &body_tables : nullptr)) {
                if (!backend_build.fault().empty()) throw InstabilityError(backend_build.fault());
                times.migrate += backend_build.take_migration_seconds();
                list_offset = backend_build.offsets();
                list_index = backend_build.neighbours();
                reference_on_backend = backend_build.reference();
                if (bodies()) constituents_on_backend = backend_build.constituents();
                built_on_backend = true;
                reference_copied = false;
                moved_since_build = false;
                ++rebuilds;
                check_count();
                return;
            }
        }
        built_on_backend = false;
        // Host code (decomposition, cells, list) that reorders and resizes every array; forces
        // are recomputed after it.
        host_reads(kAllFields & ~kForce);
        host_wrote(kAllFields);
        if (!boundaries.empty()) agree_on_boundary_faults();
        bodies_to_host(kBodyFields);  // bodies migrate and place their constituents (host code)
        bodies_host_wrote(kBodyFields);
        if (bodies()) rigid.drop_constituents(store);
        {
            PhaseTimer migrating(times.migrate);
            migration.apply(store, *grid);
            // Bodies move whole, by their centre of mass; their spheres follow.
            if (bodies() && !bodies_dealt) rigid.migrate(*grid);
            bodies_dealt = false;
        }
        if (bodies()) rigid.append_constituents(store);
        if (!restored_reference.empty()) {
            // Spheres come with their bodies (io::restore_checkpoint deals them so); one that
            // did not is binned at its body's pose.
            for (std::size_t i = 0; i < store.n_owned(); ++i)
                if (const Vec3* at = is_free(i) ? nullptr : find_by_id(restored_reference, store.id[i]))
                    store.position[i] = *at;
            std::vector<std::pair<std::int64_t, Vec3>>().swap(restored_reference);
        }
        // Cell order gives the force loop neighbours that sit close in memory.
        cells.sort_order(store.position.data(), store.id.data(), store.n_owned(), order);
        if (interior_first) order_interior_first();
        store.permute_owned(order, kAllFields & ~kForce);  // forces are recomputed after a build
        halo.build(store, *grid, ghost_width(), ghost_fields);
        cells.bin_after_sort(store.position.data(), store.size());
        // Wedge images turned by other than a quarter or half turn land inside the domain's
        // cells, so the search cannot assume those hold owned particles only.
        const bool mixed_cells =
            bodies() || (box.wedge.active() && box.wedge.n != 2 && box.wedge.n != 4);
        if (full_list) {
            list.build_full(store, cells);
            place_full_list();
        } else {
            list.build(store, cells, mixed_cells);
            if (interior_first) check_interior();
        }
        moved_since_build = false;
        if (mirror) {
            const std::vector<Vec3>& reference = list.reference_positions();
            reference_on_backend = static_cast<const Vec3*>(
                mirror->upload(kReference, reference.data(), reference.size() * sizeof(Vec3)));
            backend_halo.place(halo, *mirror, kHaloIndex);
        }
        if (bodies()) {
            rigid.index_constituents(store);
            place_constituents();
        }
        ++rebuilds;
        check_count();
    }

    /// Each owned particle's work (decomp::kParticleCost): its entries in the list last built,
    /// wherever that list lives, plus the fixed share.
    const std::vector<std::uint32_t>& particle_costs() const {
        const std::size_t n = store.n_owned();
        const std::uint32_t* offset = list.offsets();
        if (built_on_backend) {
            offset_copy.resize(n + 1);
            mirror->copy_to_host(offset_copy.data(), backend_build.offsets(), (n + 1) * sizeof(std::uint32_t));
            offset = offset_copy.data();
        } else if (list.n_owned() != n) {
            throw std::logic_error("particle_costs: the list does not match the particles");
        }
        cost_scratch.resize(n);
        for (std::size_t i = 0; i < n; ++i) cost_scratch[i] = offset[i + 1] - offset[i] + decomp::kParticleCost;
        return cost_scratch;
    }

    /// Moves the planes between domains to equal shares of the work (LoadBalance::Cost); where
    /// they moved (returns true) a build must follow, which takes the particles to their new
    /// owners. Collective.
    bool rebalance() {
        PhaseTimer timer(times.neighbour);
        host_reads(kPosition);
        const std::vector<std::uint32_t>& cost = particle_costs();
        // Particles may be up to about half the skin outside their domain when a build is due:
        // planes stay a skin inside the neighbouring domains, so one migration pass suffices.
        const decomp::BalanceReport report = decomp::balance_cuts(
            *grid, store.position.data(), cost.data(), store.n_owned(), ghost_width(), settings.skin);
        if (balance_stats.rebalances == 0) balance_stats.imbalance_first = report.imbalance_before;
        balance_stats.imbalance_last = report.imbalance_before;
        ++balance_stats.rebalances;
        if (report.axes_moved == 0) return false;
        cells.setup(grid->lo(), grid->hi(), ghost_width(), list.list_cutoff(), settings.cell_subdivisions);
        return true;
    }

    /// Puts first, in `order`, the owned particles farther than the list range from every face
    /// that brings ghosts (a neighbour's, or the rank's own periodic images): no ghost can be
    /// in their rows of the list. Each part keeps its cell order.
    void order_interior_first() {
        const Vec3 lo = grid->lo(), hi = grid->hi();
        // The search's range, widened as its single-precision copy widens it (NeighbourList).
        const double range = list.list_cutoff() + cells.binned_distance_error();
        bool low[3], high[3];
        for (int d = 0; d < 3; ++d) {
            low[d] = grid->neighbour(d, 0) != MPI_PROC_NULL;
            high[d] = grid->neighbour(d, 1) != MPI_PROC_NULL;
        }
        n_interior = cells.partition_sorted(order, [&](std::uint32_t i) {
            const Vec3& x = store.position[i];
            for (int d = 0; d < 3; ++d)
                if ((low[d] && x[d] - lo[d] <= range) || (high[d] && hi[d] - x[d] <= range)) return false;
            return true;
        });
    }

    /// The rows of the interior particles hold no ghost (what the overlap relies on).
    void check_interior() const {
        const std::uint32_t *offset = list.offsets(), *nb = list.neighbours();
        const std::size_t n_owned = store.n_owned();
        for (std::uint32_t k = 0; k < offset[n_interior]; ++k)
            if (nb[k] >= n_owned) throw std::logic_error("an interior particle has a ghost in its list row");
    }

    /// After a build: no particle was lost or made on the way. Collective.
    void check_count() const {
        const long long n = decomp::sum(comm, static_cast<long long>(store.n_owned()));
        if (n != n_global) {
            std::ostringstream msg;
            msg << "particle count changed from " << n_global << " to " << n << " at step " << step;
            throw InstabilityError(msg.str());
        }
    }

    /// Forces at the current positions, which are those of time `at` (walls that move with
    /// time are placed there).
    void compute_forces(bool sample, double at) {
        PhaseTimer timer(times.force);
        if (full_list) {
            backend_reads(particle_fields | ghost_fields | kSpecies);
            BackendParticles particles = backend_particles();
            sums = ForceSums{};
            ForceContext context{&mass, box, at};
            // A first term that writes every owned force spares the pass clearing them; the
            // ghosts' are cleared all the same.
            const bool replace = !bodies() && !forces.empty() && forces.front()->stores_on_backend();
            const std::size_t cleared = replace ? particles.n_owned : 0;
            exec::for_each(target, particles.size - cleared, integrate::ZeroVector{particles.force + cleared});
            for (const auto& term : forces) {
                context.replace_forces = replace && term == forces.front();
                term->add_forces_on_backend(particles, context, sample, sums);
            }
            backend_wrote(kForce);
            if (bodies()) {
                rigid.sum_forces(target, body_arrays(kPosition), data(kPosition, store.position),
                                 data(kForce, store.force));
                bodies_wrote(kForce | kTorque);
            }
            return;
        }
        // Force terms in their host form: host code on the store.
        host_reads(particle_fields | ghost_fields | (bodies() ? kPosition | kBody : 0u));
        std::fill(store.force.begin(), store.force.end(), Vec3{0, 0, 0});
        sums = ForceSums{};
        const ForceContext context{&mass, box, at};
        if (refresh_in_flight) {
            // The first (pair) term's interior rows while the ghosts arrive, a share of them per
            // stage of the refresh; then its other rows and every other term, in the order of
            // the plain loop below, so each force sums the same terms in the same order.
            // Each stage's share goes in kPokes pieces with a call into MPI between them, so
            // that large messages' handshakes go on while the rows are summed.
            constexpr std::size_t kPokes = 8;
            ForceContext rows = context;
            const std::size_t stages = halo.refresh_stages(), pieces = stages * kPokes;
            for (std::size_t k = 0; k < pieces; ++k) {
                rows.first = n_interior * k / pieces;
                rows.last = n_interior * (k + 1) / pieces;
                forces.front()->add_forces(store, list, rows, sample, sums);
                if ((k + 1) % kPokes == 0)
                    halo.advance_refresh();
                else
                    halo.progress();
            }
            halo.end_refresh();
            refresh_in_flight = false;
            rows.first = n_interior;
            rows.last = static_cast<std::size_t>(-1);
            forces.front()->add_forces(store, list, rows, sample, sums);
            for (std::size_t k = 1; k < forces.size(); ++k) forces[k]->add_forces(store, list, context, sample, sums);
        } else {
            for (const auto& term : forces) term->add_forces(store, list, context, sample, sums);
        }
        host_wrote(kForce);
        if (bodies()) {
            // Host code summed the forces: the bodies' sums run on the host too.
            bodies_to_host(kPosition);
            rigid.sum_forces(exec::Target{}, rigid.host_arrays(), store.position.data(), store.force.data());
            bodies_host_wrote(kForce | kTorque);
        }
    }

    /// v += kick f/m, x += drift v; then the walls act on the drift.
    void kick_drift(double kick, double drift, double at) {
        PhaseTimer timer(times.integrate);
        moved_since_build = true;
        backend_reads(kPosition | kVelocity | kForce | kSpecies);
        const integrate::KickDrift stage{data(kPosition, store.position), data(kVelocity, store.velocity),
                                         data(kForce, store.force), data(kSpecies, store.species),
                                         inverse_masses(), kick, drift};
        // Where the drift is the last move before the rebuild test, the test is taken in the
        // same pass: one read of the positions fewer, and on a device one launch fewer.
        if (const Vec3* x0 = boundaries.empty() && !bodies() ? check_origin() : nullptr) {
            drift_moved_sq = exec::transform_max(
                target, store.n_owned(), 0.0,
                exec::Then<integrate::KickDrift, SquaredDisplacement>{stage, {stage.x, x0}});
            drift_moved_known = true;
        } else {
            exec::for_each(target, store.n_owned(), stage);
        }
        backend_wrote(kPosition | kVelocity);
        // Spheres of bodies were moved as free particles above; the bodies now place them.
        if (bodies()) {
            rigid.kick_drift(target, body_arrays(kPosition | kVelocity | kForce | kSpecies | kOrientation |
                                                 kAngularMomentum | kTorque),
                             data(kPosition, store.position), data(kVelocity, store.velocity), kick, drift);
            bodies_wrote(kPosition | kVelocity | kOrientation | kAngularMomentum);
            backend_wrote(kPosition | kVelocity);
        }
        if (boundaries.empty()) return;
        backend_reads(kPosition | kVelocity | kSpecies | kId);
        const BackendParticles particles = backend_particles();
        const BoundaryContext context{drift, step, &box, at};
        for (auto& rule : boundaries) rule->apply(particles, context, boundary_fault);
        backend_wrote(kPosition | kVelocity);
    }

    void kick(double kick) {
        PhaseTimer timer(times.integrate);
        backend_reads(kVelocity | kForce | kSpecies);
        const integrate::Kick stage{data(kVelocity, store.velocity), data(kForce, store.force),
                                    data(kSpecies, store.species), inverse_masses(), kick};
        // The thermostat that follows needs the kinetic energy: summed in the same pass.
        if (thermostat && !bodies()) {
            kick_kinetic = exec::transform_sum<double>(
                target, store.n_owned(),
                exec::Then<integrate::Kick, integrate::FreeKineticEnergy>{stage, kinetic_energy()});
            kick_kinetic_known = true;
        } else {
            exec::for_each(target, store.n_owned(), stage);
        }
        backend_wrote(kVelocity);
        if (bodies()) {
            // The step's Langevin pass sets the constituents' velocities again before anything
            // reads them (the thermostat reads the free particles' alone).
            rigid.kick(target, body_arrays(kPosition | kVelocity | kForce | kSpecies | kOrientation |
                                           kAngularMomentum | kTorque),
                       data(kPosition, store.position), data(kVelocity, store.velocity), kick,
                       !body_langevin);
            bodies_wrote(kVelocity | kAngularMomentum);
            backend_wrote(kVelocity);
        }
    }

    /// After a drift: the list is rebuilt if some particle moved beyond half the skin since
    /// the last build, otherwise the ghosts follow their owners.
    /// `defer`: the forces that follow are not sampled, so the ghosts' refresh may overlap
    /// them (overlap_now()).
    void follow_drift(bool defer) {
        bool needed;
        {
            PhaseTimer timer(times.communicate);
            double local;
            if (drift_moved_known) {
                drift_moved_known = false;
                local = drift_moved_sq;
            } else if (mirror) {
                backend_reads(kPosition);
                local = exec::transform_max(target, store.n_owned(), 0.0,
                                            SquaredDisplacement{mirror->array<Vec3>(kPosition), reference_on_backend});
            } else {
                local = list.max_displacement_sq(store);
            }
            PhaseTimer voting(times.collective_wait);
            needed = list.rebuild_due(local, comm);
        }
        if (balance_due) {
            balance_due = false;
            if (rebalance()) needed = true;
        }
        if (needed) {
            built_this_step = true;
            rebuild(true);
            return;
        }
        PhaseTimer timer(times.communicate);
        // Contact forces with damping or friction need their partners' velocities too.
        if (mirror) {
            Vec3* x = mirror->array<Vec3>(kPosition);
            backend_halo.gather(target, halo, *mirror, x, true, kHaloPack);
            backend_wrote(kPosition);
            if (ghost_fields & kVelocity) {
                backend_reads(kVelocity);
                backend_halo.gather(target, halo, *mirror, mirror->array<Vec3>(kVelocity), false, kHaloPack);
                backend_wrote(kVelocity);
            }
        } else if (defer && overlap_now()) {
            halo.begin_refresh(store, (ghost_fields & kVelocity) != 0);
            refresh_in_flight = true;
        } else {
            halo.gather_positions(store);
            if (ghost_fields & kVelocity) halo.gather_velocities(store);
        }
    }

    bool is_free(std::size_t i) const { return !store.has_rigid_fields() || store.body[i] < 0; }

    /// A free particle's kinetic energy, on the back end's arrays.
    integrate::FreeKineticEnergy kinetic_energy() const {
        backend_reads(kVelocity | kSpecies | kBody);
        return {data(kVelocity, store.velocity), data(kSpecies, store.species), masses(),
                store.has_rigid_fields() ? data(kBody, store.body) : nullptr};
    }

    /// Kinetic energy of free particles and bodies (spheres of bodies count through them).
    double local_kinetic() const {
        const double sum = exec::transform_sum<double>(target, store.n_owned(), kinetic_energy());
        return sum + (bodies() ? rigid.kinetic(target, body_arrays(kVelocity | kSpecies | kOrientation |
                                                                    kAngularMomentum))
                               : 0.0);
    }

    long long n_free = 0, n_bodies = 0;

    double dof() const {
        const bool periodic = box.periodic[0] && box.periodic[1] && box.periodic[2];
        // In a fully periodic box total momentum is conserved: 3 fewer degrees of freedom.
        const double all = bodies() ? 3.0 * n_free + 6.0 * n_bodies : 3.0 * n_global;
        return all - (periodic ? 3.0 : 0.0);
    }

    void count_bodies() {
        long long free_here = 0;
        host_reads(kBody);
        for (std::size_t i = 0; i < store.n_owned(); ++i) free_here += is_free(i);
        n_free = decomp::sum(comm, free_here);
        n_bodies = decomp::sum(comm, static_cast<long long>(rigid.n_owned()));
    }

    /// Where this step rebuilt the list, the slot its first global sum's wait also goes to.
    double* after_build_wait() { return built_this_step ? &times.collective_wait_after_build : nullptr; }

    void apply_thermostat() {
        if (!thermostat) return;
        PhaseTimer timer(times.integrate);
        if (bodies()) {
            // With rigid bodies the thermostat acts on the free particles alone (an explicit
            // solvent bath), about their mean velocity; the bodies take the bath's temperature
            // through collisions only.
            backend_reads(kVelocity | kSpecies | kBody);
            const integrate::MassMotion local = exec::transform_sum<integrate::MassMotion>(
                target, store.n_owned(),
                integrate::FreeMassMotion{data(kVelocity, store.velocity), data(kSpecies, store.species),
                                          masses(), data(kBody, store.body)});
            double sums[5] = {local.mass, local.kinetic, local.momentum.x, local.momentum.y,
                              local.momentum.z};
            {
                PhaseTimer summing(times.collective_wait, after_build_wait());
                MPI_Allreduce(MPI_IN_PLACE, sums, 5, MPI_DOUBLE, MPI_SUM, comm);
            }
            if (n_free < 2 || !(sums[0] > 0)) return;
            const Vec3 momentum{sums[2], sums[3], sums[4]};
            const double relative = sums[1] - 0.5 * dot(momentum, momentum) / sums[0];
            const double factor =
                thermostat->scale_factor(relative, 3.0 * double(n_free) - 3.0, step, settings.dt);
            exec::for_each(target, store.n_owned(),
                           integrate::ScaleFreeAboutMean{data(kVelocity, store.velocity),
                                                         data(kBody, store.body),
                                                         (1 / sums[0]) * momentum, factor});
            backend_wrote(kVelocity);
            return;
        }
        const double local = kick_kinetic_known ? kick_kinetic : local_kinetic();
        kick_kinetic_known = false;
        double kinetic;
        {
            PhaseTimer summing(times.collective_wait, after_build_wait());
            kinetic = decomp::sum(comm, local);
        }
        const double factor = thermostat->scale_factor(kinetic, dof(), step, settings.dt);
        exec::for_each(target, store.n_owned(),
                       integrate::ScaleVelocity{data(kVelocity, store.velocity), factor});
        backend_wrote(kVelocity);
    }

    void apply_body_langevin() {
        if (!body_langevin || !bodies()) return;
        PhaseTimer timer(times.integrate);
        backend_reads(kPosition | kVelocity);
        const double dt = settings.dt;
        rigid.langevin(target, body_arrays(kPosition | kVelocity | kSpecies | kId | kOrientation | kAngularMomentum),
                       data(kPosition, store.position), data(kVelocity, store.velocity),
                       std::exp(-body_langevin->translation_rate * dt),
                       std::exp(-body_langevin->rotation_rate * dt), body_langevin->temperature,
                       body_langevin->seed, static_cast<std::uint64_t>(step));
        bodies_wrote(kVelocity | kAngularMomentum);
        backend_wrote(kVelocity);
    }

    void apply_wall_layers() {
        if (wall_layers.empty()) return;
        PhaseTimer timer(times.integrate);
        backend_reads(kPosition | kVelocity | kSpecies);
        const BackendParticles particles = backend_particles();
        for (auto& layer : wall_layers) layer->apply(particles, comm, step);
        backend_wrote(kVelocity);
    }

    void require_grid(const char* what) const {
        if (!grid) throw std::logic_error(std::string(what) + ": set_box first");
    }
};

Simulation::Simulation(MPI_Comm comm, const RunSettings& settings)
    : engine_(std::make_unique<Engine>()) {
    engine_->comm = comm;
    engine_->settings = settings;
    switch (settings.backend) {
    case Backend::Host:
        break;
    case Backend::Checking:
        engine_->mirror = std::make_unique<exec::ParticleMirror>(exec::separate_host_memory(), true);
        engine_->body_mirror = std::make_unique<exec::ParticleMirror>(exec::separate_host_memory(), true);
        engine_->target.separate = true;
        break;
    case Backend::Cuda:
        if (!gpu::device_present())
            throw InputError("backend=cuda: no CUDA device is visible to this process "
                             "(or the build has no CUDA); use backend=host");
        // One device per rank (node-local rank modulo the devices); the particle data live
        // there for the whole run, on the default stream.
        engine_->mirror = std::make_unique<exec::ParticleMirror>(exec::cuda_device_memory(), false);
        engine_->body_mirror = std::make_unique<exec::ParticleMirror>(exec::cuda_device_memory(), false);
        engine_->target.device = true;
        engine_->target.separate = true;
        break;
    }
}

Simulation::~Simulation() = default;

void Simulation::set_box(const Box& box, const bool split_axis[3]) {
    // Beyond 1e9 sigma from the origin a double position resolves ~1e-7 and worse: a step's
    // displacement is rounded away (at 1e100 x + v dt == x), and the cell grid alone would
    // not fit in memory. A box that large is a parameter gone wrong (a density of 1e-300).
    constexpr double kFarthest = 1e9;
    for (int d = 0; d < 3; ++d)
        if (!(box.hi[d] > box.lo[d])) {
            std::ostringstream msg;
            msg << "box: axis " << "xyz"[d] << " has length " << box.hi[d] - box.lo[d]
                << ", must be > 0";
            throw InputError(msg.str());
        } else if (!(std::abs(box.lo[d]) <= kFarthest && std::abs(box.hi[d]) <= kFarthest)) {
            std::ostringstream msg;
            msg << "box: axis " << "xyz"[d] << " spans " << box.lo[d] << " to " << box.hi[d]
                << ", beyond " << kFarthest << " sigma from the origin, where positions lose a "
                << "step's displacement to round-off: check the parameters that size the box "
                << "(density, particle fraction, dimensions)";
            throw InputError(msg.str());
        }
    bool split[3] = {true, true, true};
    if (split_axis) std::copy(split_axis, split_axis + 3, split);
    if (box.wedge.active()) {
        if (box.periodic[0] || box.periodic[1])
            throw InputError("box: a wedge region needs x and y bounded (not periodic)");
        if (box.wedge.n < 2) throw InputError("box: a wedge needs n >= 2 (n = 1 is the full circle)");
        split[0] = split[1] = false;  // both cut faces must be on every rank
    }
    engine_->box = box;
    engine_->grid = std::make_unique<decomp::RankGrid>(engine_->comm, box, engine_->settings.grid,
                                                       split);
}

void Simulation::set_species_masses(const std::vector<double>& masses) {
    engine_->mass.assign(masses.begin(), masses.end());
    engine_->inverse_mass.clear();
    for (double m : masses) {
        // Mass 0: points without inertia (attraction sites), only as constituents of bodies.
        if (!(m >= 0)) throw InputError("species mass " + std::to_string(m) + " must be >= 0");
        engine_->inverse_mass.push_back(m > 0 ? 1.0 / m : 0.0);
    }
}

void Simulation::set_body_langevin(const BodyLangevinSettings& settings) {
    if (!(settings.temperature >= 0) || !(settings.translation_rate >= 0) || !(settings.rotation_rate >= 0))
        throw InputError("body Langevin: temperature and rates must be >= 0");
    engine_->body_langevin = settings;
}

void Simulation::add_force(std::unique_ptr<ForceTerm> term) {
    engine_->ghost_fields |= term->ghost_fields();
    engine_->particle_fields |= term->particle_fields();
    engine_->forces.push_back(std::move(term));
}

BoundaryRule* Simulation::add_boundary(std::unique_ptr<BoundaryRule> rule) {
    engine_->boundaries.push_back(std::move(rule));
    return engine_->boundaries.back().get();
}

WallLayerThermostat* Simulation::add_wall_layer(std::unique_ptr<WallLayerThermostat> layer) {
    engine_->wall_layers.push_back(std::move(layer));
    return engine_->wall_layers.back().get();
}

std::vector<const BoundaryRule*> Simulation::boundary_rules() const {
    std::vector<const BoundaryRule*> rules;
    for (const auto& rule : engine_->boundaries) rules.push_back(rule.get());
    return rules;
}

WallExchange Simulation::global_exchange(const BoundaryRule& rule) const {
    const WallExchange& w = rule.exchange();
    double v[6] = {static_cast<double>(w.hits), w.momentum.x, w.momentum.y, w.momentum.z,
                   w.angular_momentum, w.energy};
    decomp::sum_in_place(engine_->comm, v, 6);
    WallExchange total;
    total.hits = static_cast<long long>(v[0]);
    total.momentum = {v[1], v[2], v[3]};
    total.angular_momentum = v[4];
    total.energy = v[5];
    return total;
}

void Simulation::set_thermostat(std::unique_ptr<Thermostat> thermostat) {
    engine_->thermostat = std::move(thermostat);
}

void Simulation::add_particle(const Vec3& x, const Vec3& v, int species, std::int64_t id,
                              double diameter) {
    Engine& e = *engine_;
    e.require_grid("add_particle");
    const Vec3 lo = e.grid->lo(), hi = e.grid->hi();
    for (int d = 0; d < 3; ++d)
        if (x[d] < lo[d] || x[d] >= hi[d]) return;
    if (species < 0 || species >= static_cast<int>(e.mass.size()))
        throw InputError("particle species " + std::to_string(species) + " has no mass set");
    if (!(e.mass[std::size_t(species)] > 0))
        throw InputError("particle species " + std::to_string(species) +
                         " has mass 0: such points exist only as constituents of rigid bodies");
    if (!(diameter > 0)) throw InputError("particle diameter " + std::to_string(diameter) + " must be > 0");
    e.host_reads(kAllFields);
    // A set-up adds its particles one at a time: room doubles here, where the store's own
    // growth by 1/32 (kept for the run's migrations) would copy every array ~30 times into
    // fresh pages. The store is fitted to its size when the set-up ends.
    if (e.store.n_owned() + 1 > e.store.position.capacity())
        e.store.reserve(std::max<std::size_t>(1024, 2 * (e.store.n_owned() + 1)));
    e.store.add_owned(x, v, species, id, diameter);
    e.host_wrote(kAllFields);
}

void Simulation::assign_thermal_velocities(double temperature, std::uint64_t seed) {
    Engine& e = *engine_;
    ParticleStore& s = e.store;
    e.host_reads(kVelocity | kSpecies | kId);
    e.host_wrote(kVelocity);
    e.n_global = decomp::sum(e.comm, static_cast<long long>(s.n_owned()));
    // Exact (order-independent) sums: the initial state is bitwise the same on any rank count.
    decomp::ExactSum p[3], total_mass, kinetic;
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        const double m = e.mass[s.species[i]];
        const auto id = static_cast<std::uint64_t>(s.id[i]);
        for (int d = 0; d < 3; ++d) {
            s.velocity[i][d] = std::sqrt(temperature / m) * gaussian(seed, id, d);
            p[d].add(m * s.velocity[i][d]);
        }
        total_mass.add(m);
    }
    const double mass = total_mass.global(e.comm);
    const Vec3 drift{p[0].global(e.comm) / mass, p[1].global(e.comm) / mass,
                     p[2].global(e.comm) / mass};
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        s.velocity[i] -= drift;
        kinetic.add(0.5 * e.mass[s.species[i]] * dot(s.velocity[i], s.velocity[i]));
    }
    const double k = kinetic.global(e.comm);
    const double factor = k > 0 ? std::sqrt(0.5 * e.dof() * temperature / k) : 0.0;
    for (std::size_t i = 0; i < s.n_owned(); ++i) s.velocity[i] *= factor;
}

void Simulation::initialise() {
    Engine& e = *engine_;
    e.prepare();
    if (e.bodies()) {
        // The spheres of bodies appear with the first build: count them in beforehand.
        e.rigid.drop_constituents(e.store);
        e.rigid.append_constituents(e.store);
        e.n_global = decomp::sum(e.comm, static_cast<long long>(e.store.n_owned()));
    }
    e.place_body_frames();
    e.rebuild();
    if (e.settings.balance == LoadBalance::Cost && e.rebalance()) e.rebuild();
    e.count_bodies();
    e.compute_forces(true, e.time);
}

void Simulation::check_guards(const GuardLimits& limits) const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    std::string problem = e.boundary_fault;
    const double f2max = limits.max_force * limits.max_force;
    e.backend_reads(kPosition | kVelocity | kForce);
    const integrate::UnfitState unfit{e.data(kPosition, s.position), e.data(kVelocity, s.velocity),
                                      e.data(kForce, s.force), f2max};
    const std::size_t i = problem.empty() ? exec::first_index(e.target, s.n_owned(), unfit) : s.n_owned();
    if (i < s.n_owned()) {
        e.host_reads(kPosition | kVelocity | kForce | kId);  // to name the offender
        const Vec3 &x = s.position[i], &v = s.velocity[i], &f = s.force[i];
        const bool finite = std::isfinite(x.x + x.y + x.z + v.x + v.y + v.z + f.x + f.y + f.z);
        std::ostringstream msg;
        if (!finite)
            msg << "particle id " << s.id[i] << " has a non-finite position, velocity or force";
        else
            msg << "force " << std::sqrt(dot(f, f)) << " on particle id " << s.id[i]
                << " exceeds guard.max_force=" << limits.max_force
                << " (overlapping particles or a time step too large)";
        problem = msg.str() + " at step " + std::to_string(engine_->step);
    }
    const std::string message = decomp::first_message(engine_->comm, problem);
    if (!message.empty()) throw InstabilityError(message);
}

StateSnapshot Simulation::snapshot() const {
    StateSnapshot snap;
    snapshot(snap);
    return snap;
}

void Simulation::snapshot(StateSnapshot& snap) const {
    const Engine& e = *engine_;
    // The owned part of each field the restore needs (ghosts are rebuilt). Forces are kept only
    // where they depend on velocities, which restore cannot recompute them from; conservative
    // forces are recomputed. Of the rigid fields spheres need only their body's id. Species and
    // diameters the same for every particle here are left to their fill values (0 and 1).
    const ParticleStore& s = e.store;
    const auto n = static_cast<std::ptrdiff_t>(s.n_owned());
    e.host_reads(kPosition | kVelocity | kId | kImage | kBody | kForce | kSpecies | kDiameter);
    unsigned fields = kPosition | kVelocity | kId | kImage | kBody;
    if (e.ghost_fields & kVelocity) fields |= kForce;
    if (std::any_of(s.species.begin(), s.species.begin() + n, [](int k) { return k != 0; })) fields |= kSpecies;
    if (s.has_diameters() &&
        std::any_of(s.diameter.begin(), s.diameter.begin() + n, [](Real d) { return d != 1; }))
        fields |= kDiameter;
    snap.owned.copy_owned(s, fields);
    if (e.moved_since_build)
        snap.reference = e.reference_positions();
    else
        std::vector<Vec3>().swap(snap.reference);
    if (e.bodies()) {
        e.bodies_to_host(Engine::kBodyFields);
        snap.bodies = e.rigid.bodies();
    }
    snap.domain_cuts = domain_cuts();
    snap.step = e.step;
    snap.time = e.time;
    snap.rebuilds = e.rebuilds;
}

void Simulation::restore(const StateSnapshot& snapshot) {
    ParticleStore copy = snapshot.owned;
    const bool saved_forces = !copy.force.empty();
    copy.resize_owned(copy.n_owned());  // the arrays the snapshot left empty, at their fill values
    std::vector<Vec3> reference = snapshot.reference.empty() ? copy.position : snapshot.reference;
    ParticleStore bodies = snapshot.bodies;
    if (!snapshot.domain_cuts.empty()) set_domain_cuts(snapshot.domain_cuts);
    restore(std::move(copy), std::move(reference), snapshot.step, snapshot.time,
            snapshot.rebuilds, engine_->bodies() ? &bodies : nullptr, saved_forces);
}

std::vector<double> Simulation::field_sums(const FieldGeometry& grid) const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    const std::size_t n = s.n_owned(), cells = static_cast<std::size_t>(grid.n_cells());
    std::vector<double> sums(cells * observe::kFieldSums);
    if (!e.mirror) {
        observe::scatter_field_sums(grid, e.box, n, s.position.data(), s.velocity.data(), s.species.data(),
                                    e.mass.data(), sums.data());
        return sums;
    }
    // Where the particles live: sorted by cell (stably, so each cell's members in index order),
    // each cell summed in that order; only the sums come back.
    e.backend_reads(kPosition | kVelocity | kSpecies);
    exec::ParticleMirror& m = *e.mirror;
    auto* key = static_cast<std::uint32_t*>(m.scratch(Engine::kFieldKeys, n * sizeof(std::uint32_t)));
    auto* member = static_cast<std::uint32_t*>(m.scratch(Engine::kFieldMembers, n * sizeof(std::uint32_t)));
    auto* start = static_cast<std::uint32_t*>(m.scratch(Engine::kFieldStart, (cells + 1) * sizeof(std::uint32_t)));
    auto* out = static_cast<double*>(m.scratch(Engine::kFieldSums, sums.size() * sizeof(double)));
    const Vec3* x = e.data(kPosition, s.position);
    exec::for_each(e.target, n, observe::FieldCellKey{grid, e.box, x, key, member});
    exec::sort_pairs(e.target, key, member, n, build::key_bits(cells + 1));
    exec::for_each(e.target, cells + 1, build::CellStart{key, n, start});
    exec::for_each(e.target, cells,
                   observe::FieldCellSums{grid, e.box, x, e.data(kVelocity, s.velocity), e.data(kSpecies, s.species),
                                          e.masses(), start, member, out});
    m.copy_to_host(sums.data(), out, sums.size() * sizeof(double));
    return sums;
}

const std::vector<Vec3>& Simulation::list_reference_positions() const {
    return engine_->reference_positions();
}

int Simulation::rank_of(const Vec3& x) const {
    engine_->require_grid("rank_of");
    return engine_->grid->rank_of(x);
}

std::vector<double> Simulation::domain_cuts() const {
    engine_->require_grid("domain_cuts");
    std::vector<double> planes;
    for (int d = 0; d < 3; ++d)
        planes.insert(planes.end(), engine_->grid->cuts(d).begin(), engine_->grid->cuts(d).end());
    return planes;
}

void Simulation::set_domain_cuts(const std::vector<double>& planes) {
    Engine& e = *engine_;
    e.require_grid("set_domain_cuts");
    const Int3 dims = e.grid->dims();
    if (planes.size() != static_cast<std::size_t>(dims.x + dims.y + dims.z + 3))
        throw InputError("domain cuts: " + std::to_string(planes.size()) + " planes do not fit a " +
                         std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                         std::to_string(dims.z) + " rank grid");
    std::size_t at = 0;
    for (int d = 0; d < 3; ++d) {
        const std::vector<double> axis(planes.begin() + at, planes.begin() + at + dims[d] + 1);
        at += axis.size();
        bool fits = axis.front() == e.box.lo[d] && axis.back() == e.box.hi[d];
        for (std::size_t k = 1; fits && k < axis.size(); ++k) fits = axis[k] > axis[k - 1];
        if (!fits)
            throw InputError(std::string("domain cuts: the planes along ") + "xyz"[d] +
                             " do not cut this box in increasing order");
        e.grid->set_cuts(d, axis);
    }
}

const LoadBalanceStats& Simulation::load_balance() const { return engine_->balance_stats; }

bool Simulation::halo_overlap() const { return engine_->interior_first && engine_->settings.overlap_halo; }

double Simulation::interior_fraction() const {
    const Engine& e = *engine_;
    return e.interior_first && e.store.n_owned() ? double(e.n_interior) / double(e.store.n_owned()) : 0.0;
}

double Simulation::cost_imbalance() const {
    const Engine& e = *engine_;
    const std::vector<std::uint32_t>& cost = e.particle_costs();
    return decomp::cost_imbalance(e.comm, cost.data(), cost.size());
}

void Simulation::restore(ParticleStore&& owned, std::vector<Vec3>&& reference, long long step,
                         double time, long long rebuilds, ParticleStore* bodies, bool saved_forces) {
    Engine& e = *engine_;
    if (e.bodies() != (bodies != nullptr))
        throw InputError("restore: the saved state and this scene disagree about rigid bodies");
    // The bodies' saved poses by id, set again after the build below (which bins their spheres
    // at the saved list references and leaves the bodies on the ranks they were dealt to).
    std::vector<std::pair<std::int64_t, std::pair<Vec3, Int3>>> saved_bodies;
    if (bodies) {
        for (std::size_t b = 0; b < bodies->n_owned(); ++b)
            saved_bodies.push_back({bodies->id[b], {bodies->position[b], bodies->image[b]}});
        std::sort(saved_bodies.begin(), saved_bodies.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        e.rigid.store() = std::move(*bodies);
        e.bodies_host_wrote(Engine::kBodyFields);
        if (!owned.has_rigid_fields()) owned.enable_rigid_fields();
        // Spheres not dealt with their bodies cannot be indexed: every rank stops with the first.
        const std::string problem = decomp::first_message(e.comm, e.rigid.check_constituents(owned));
        if (!problem.empty()) throw InputError(problem);
    }
    if (reference.size() != owned.n_owned()) throw std::logic_error("restore: size mismatch");
    // The list is rebuilt from the positions it was originally built from, which reorders the
    // particles: their current positions and saved forces are kept by id meanwhile.
    std::vector<std::pair<std::int64_t, std::size_t>> by_id(owned.n_owned());
    for (std::size_t i = 0; i < owned.n_owned(); ++i) by_id[i] = {owned.id[i], i};
    std::sort(by_id.begin(), by_id.end());
    std::vector<Vec3> current = owned.position, forces = std::move(owned.force);
    owned.force.assign(current.size(), Vec3{0, 0, 0});  // every array whole: the build permutes all
    owned.position.assign(reference.begin(), reference.end());
    owned.position.resize(current.size());
    e.store = std::move(owned);
    e.host_wrote(kAllFields);  // what lived on the back end belongs to the state left behind
    ParticleStore& s = e.store;
    e.prepare();
    e.place_body_frames();
    if (bodies) {
        e.bodies_dealt = true;
        e.restored_reference.resize(by_id.size());
        for (std::size_t k = 0; k < by_id.size(); ++k)
            e.restored_reference[k] = {by_id[k].first, reference[by_id[k].second]};
    }
    e.rebuild();
    if (bodies) {
        // Each body where the saved state had it (unwrapped, with its image), and its spheres
        // placed from that pose: the run's positions, bit for bit.
        ParticleStore& b = e.rigid.store();
        const auto& first = e.rigid.constituent_first();
        const auto& index = e.rigid.constituent_index();
        for (std::size_t k = 0; k < b.n_owned(); ++k) {
            if (const auto* pose = find_by_id(saved_bodies, b.id[k])) {
                b.position[k] = pose->first;
                b.image[k] = pose->second;
            }
            for (std::uint32_t j = first[k]; j < first[k + 1]; ++j) s.image[index[j]] = b.image[k];
        }
        e.bodies_host_wrote(kPosition | kImage);
        e.rigid.place_at(exec::Target{}, e.rigid.host_arrays(), rigid::ConstituentIndex{first.data(), index.data()},
                         s.position.data(), s.velocity.data());
        e.host_wrote(kPosition | kVelocity | kImage);
    }
    // Where particle `id` was in the saved state on this rank, or npos: a body's spheres are
    // placed by the rank that owns the body, which need not be the rank their saved copies
    // were dealt to.
    constexpr std::size_t npos = ~std::size_t{0};
    auto saved = [&](std::int64_t id) {
        const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::make_pair(id, std::size_t{0}));
        return it != by_id.end() && it->first == id ? it->second : npos;
    };
    // Spheres of bodies were placed afresh by the build; free particles get their positions back.
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
        if (!e.is_free(i)) continue;
        const std::size_t k = saved(s.id[i]);
        if (k == npos)
            throw std::logic_error("restore: particle id " + std::to_string(s.id[i]) +
                                   " is not in this rank's saved state");
        s.position[i] = current[k];
    }
    e.halo.gather_positions(s);
    if (e.ghost_fields & kVelocity) e.halo.gather_velocities(s);
    e.host_wrote(kPosition | kVelocity);
    e.step = step;
    e.time = time;
    e.rebuilds = rebuilds;
    e.count_bodies();
    e.compute_forces(true, e.time);
    // Forces that depend on velocities (damping, friction) were computed in the run from the
    // half-step velocities, which a saved state does not hold: the saved forces continue it
    // exactly (the sums for measure() come from the recomputation).
    if (saved_forces) {
        // A sphere whose saved copy is on another rank (not from a checkpoint, whose reader
        // deals spheres with their bodies) keeps the recomputed force: with friction the
        // continuation would then stray from the uninterrupted run.
        e.host_reads(kForce | kPosition);
        for (std::size_t i = 0; i < s.n_owned(); ++i) {
            const std::size_t k = saved(s.id[i]);
            if (k != npos) s.force[i] = forces[k];
        }
        e.host_wrote(kForce);
        if (e.bodies()) {
            e.bodies_to_host(kPosition);
            e.rigid.sum_forces(exec::Target{}, e.rigid.host_arrays(), s.position.data(), s.force.data());
            e.bodies_host_wrote(kForce | kTorque);
        }
    }
}

void Simulation::step(bool sample) {
    Engine& e = *engine_;
    e.built_this_step = false;
    const double dt = e.settings.dt;
    // Rebalances by the step's index alone, so a continued run moves the planes where the
    // uninterrupted one did.
    const long long every = e.settings.balance_every;
    e.balance_due = e.settings.balance == LoadBalance::Cost && every > 0 && (e.step + 1) % every == 0;
    switch (e.settings.integrator) {
    case Integrator::VelocityVerlet:
        e.kick_drift(0.5 * dt, dt, e.time);
        e.follow_drift(!sample);
        e.compute_forces(sample, e.time + dt);
        e.kick(0.5 * dt);
        break;
    case Integrator::Omelyan: {
        // lambda minimises the norm of the leading error term (Omelyan, Mryglod & Folk,
        // Comput. Phys. Commun. 146 (2002) 188, eq. 31).
        constexpr double lambda = 0.1931833275037836;
        e.kick_drift(lambda * dt, 0.5 * dt, e.time);
        e.follow_drift(true);
        e.compute_forces(false, e.time + 0.5 * dt);
        e.kick_drift((1 - 2 * lambda) * dt, 0.5 * dt, e.time + 0.5 * dt);
        e.follow_drift(!sample);
        e.compute_forces(sample, e.time + dt);
        e.kick(lambda * dt);
        break;
    }
    }
    e.apply_thermostat();
    e.apply_body_langevin();
    ++e.step;
    e.time += dt;
    e.apply_wall_layers();  // keyed by the step just completed
}

ThermoSample Simulation::measure() const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    const Vec3 len = e.box.length();
    e.backend_reads(kPosition | kVelocity | kImage | kSpecies | kBody);
    const integrate::Momenta free = exec::transform_sum<integrate::Momenta>(
        e.target, s.n_owned(),
        integrate::FreeMomenta{e.data(kPosition, s.position), e.data(kVelocity, s.velocity),
                               e.data(kImage, s.image), e.data(kSpecies, s.species), e.masses(),
                               s.has_rigid_fields() ? e.data(kBody, s.body) : nullptr, len});
    Vec3 pb{0, 0, 0}, lb{0, 0, 0};
    if (e.bodies()) {
        const auto a = e.body_arrays(kPosition | kVelocity | kSpecies | kImage);
        pb = e.rigid.momentum(e.target, a);
        lb = e.rigid.angular_momentum(e.target, a, len);
    }
    double v[9] = {e.local_kinetic(), e.sums.potential, e.sums.virial, 0, 0, 0, 0, 0, 0};
    for (int d = 0; d < 3; ++d) v[3 + d] = free.linear[d] + pb[d], v[6 + d] = free.angular[d] + lb[d];
    decomp::sum_in_place(e.comm, v, 9);
    ThermoSample t;
    t.step = e.step;
    t.time = e.time;
    t.n = e.n_global;
    const double n = static_cast<double>(e.n_global);
    t.kinetic = v[0] / n;
    t.potential = v[1] / n;
    t.total = t.kinetic + t.potential;
    t.temperature = 2 * v[0] / e.dof();
    t.pressure = (2 * v[0] + v[2]) / (3 * e.box.volume());
    t.momentum = {v[3], v[4], v[5]};
    t.angular_momentum = {v[6], v[7], v[8]};
    MPI_Allreduce(&e.sums.max_overlap, &t.max_overlap, 1, MPI_DOUBLE, MPI_MAX, e.comm);
    return t;
}

ParticleStore& Simulation::particles() {
    engine_->host_reads(kAllFields);
    engine_->host_wrote(kAllFields);
    return engine_->store;
}
const ParticleStore& Simulation::particles() const {
    engine_->host_reads(kAllFields);
    return engine_->store;
}
const Box& Simulation::box() const { return engine_->box; }
MPI_Comm Simulation::comm() const { return engine_->comm; }
int Simulation::rank() const { return engine_->grid ? engine_->grid->rank() : 0; }
int Simulation::n_ranks() const { return engine_->grid ? engine_->grid->size() : 1; }
Int3 Simulation::rank_grid_dims() const { return engine_->grid->dims(); }
long long Simulation::n_global() const { return engine_->n_global; }
long long Simulation::step_index() const { return engine_->step; }
double Simulation::time() const { return engine_->time; }
double Simulation::dt() const { return engine_->settings.dt; }
double Simulation::measurement_start() const {
    return static_cast<double>(engine_->settings.equilibration_steps) * engine_->settings.dt;
}
long long Simulation::steps_in(double duration) const {
    return std::max<long long>(1, std::llround(duration / engine_->settings.dt));
}
double Simulation::interaction_range() const {
    double cutoff = 0;
    for (const auto& term : engine_->forces) cutoff = std::max(cutoff, term->cutoff());
    return cutoff + engine_->settings.skin;
}
KineticParts Simulation::kinetic_parts() const {
    const Engine& e = *engine_;
    e.backend_reads(kVelocity | kSpecies | kBody);
    const double free = exec::transform_sum<double>(
        e.target, e.store.n_owned(),
        integrate::FreeKineticEnergy{e.data(kVelocity, e.store.velocity), e.data(kSpecies, e.store.species),
                                     e.masses(), e.store.has_rigid_fields() ? e.data(kBody, e.store.body) : nullptr});
    const Vec3 bodies =
        e.bodies() ? e.rigid.kinetic_parts(e.target, e.body_arrays(kVelocity | kSpecies | kOrientation |
                                                                   kAngularMomentum))
                   : Vec3{0, 0, 0};
    double sums[3] = {free, bodies.x, bodies.y};
    MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, e.comm);
    KineticParts k{sums[0], sums[1], sums[2], e.bodies() ? e.n_free : e.n_global,
                   e.bodies() ? e.n_bodies : 0};
    return k;
}

long long Simulation::rebuilds() const { return engine_->rebuilds; }
double Simulation::degrees_of_freedom() const { return engine_->dof(); }
const std::vector<double>& Simulation::species_masses() const { return engine_->mass; }
Backend Simulation::backend() const { return engine_->settings.backend; }
bool Simulation::has_thermostat() const { return engine_->thermostat != nullptr; }
bool Simulation::has_bodies() const { return engine_->bodies(); }
ParticleStore& Simulation::bodies() {
    // As particles(): brought up to date, and counted as changed by the caller.
    engine_->bodies_to_host(Engine::kBodyFields);
    engine_->bodies_host_wrote(Engine::kBodyFields);
    return engine_->rigid.store();
}
long long Simulation::n_bodies_global() const { return engine_->n_bodies; }

int Simulation::add_body_kind(const std::vector<Vec3>& positions, const std::vector<int>& species,
                              const std::vector<double>& diameters) {
    Engine& e = *engine_;
    if (!e.store.has_rigid_fields()) e.store.enable_rigid_fields();
    e.ghost_fields |= kBody;
    return e.rigid.add_kind({positions, species, diameters}, e.mass);
}

void Simulation::add_body(int kind, const Vec3& com, const Quat& orientation, const Vec3& velocity,
                          const Vec3& omega, std::int64_t id, std::int64_t first_particle_id) {
    Engine& e = *engine_;
    e.require_grid("add_body");
    const Vec3 lo = e.grid->lo(), hi = e.grid->hi();
    for (int d = 0; d < 3; ++d)
        if (com[d] < lo[d] || com[d] >= hi[d]) return;
    e.rigid.add(kind, com, orientation, velocity, omega, id, first_particle_id);
}
std::vector<double> Simulation::exchange_tallies() const {
    std::vector<double> t;
    for (const auto& rule : engine_->boundaries) {
        const WallExchange e = global_exchange(*rule);
        t.insert(t.end(), {double(e.hits), e.momentum.x, e.momentum.y, e.momentum.z,
                           e.angular_momentum, e.energy});
    }
    for (const auto& layer : engine_->wall_layers) t.push_back(layer->energy());  // global already
    return t;
}

void Simulation::restore_exchange_tallies(const std::vector<double>& t) {
    Engine& e = *engine_;
    if (t.size() != 6 * e.boundaries.size() + e.wall_layers.size())
        throw InputError("checkpoint: exchange tallies of " + std::to_string(t.size()) +
                         " values do not fit this scene's walls");
    const bool keep = rank() == 0;
    std::size_t k = 0;
    for (auto& rule : e.boundaries) {
        WallExchange x;
        if (keep)
            x.hits = static_cast<long long>(t[k]), x.momentum = {t[k + 1], t[k + 2], t[k + 3]},
            x.angular_momentum = t[k + 4], x.energy = t[k + 5];
        rule->set_exchange(x);
        k += 6;
    }
    for (auto& layer : e.wall_layers) layer->set_energy(t[k++]);
}

bool Simulation::conserves_energy() const {
    if (engine_->thermostat || engine_->body_langevin || !engine_->wall_layers.empty()) return false;
    for (const auto& term : engine_->forces)
        if (!term->conservative()) return false;
    for (const auto& rule : engine_->boundaries)
        if (!rule->conservative()) return false;
    return true;
}
const PhaseTimes& Simulation::phase_times() const {
    engine_->times.halo_wait = engine_->halo.refresh_wait_seconds() - engine_->wait_at_reset;
    return engine_->times;
}

MessageTraffic Simulation::message_traffic() const {
    const Engine& e = *engine_;
    MessageTraffic t;
    t.ghost_refresh = e.halo.refresh_traffic();
    t.ghost_build = e.halo.build_traffic();
    t.ghost_build += e.backend_build.ghost_traffic();
    t.migration = e.migration.traffic();
    t.migration += e.backend_build.migration_traffic();
    t.migration += e.rigid.migration_traffic();
    const MessageTraffic& from = e.traffic_at_reset;
    auto since = [](MessageCounts now, const MessageCounts& then) {
        now.messages -= then.messages;
        now.bytes -= then.bytes;
        return now;
    };
    return {since(t.ghost_refresh, from.ghost_refresh), since(t.ghost_build, from.ghost_build),
            since(t.migration, from.migration)};
}

void Simulation::reset_phase_times() {
    engine_->times = PhaseTimes{};
    engine_->wait_at_reset = engine_->halo.refresh_wait_seconds();
    engine_->traffic_at_reset = MessageTraffic{};
    engine_->traffic_at_reset = message_traffic();
}

}  // namespace emergent
