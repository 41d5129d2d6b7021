// SPDX-License-Identifier: MIT
#include "core/neighbourhood.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "decomposition/load_balance.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "integrate/kick_drift.hpp"

namespace emergent {

namespace {
/// The value kept for `id` in pairs sorted by id, or null.
const Vec3* find_by_id(const std::vector<std::pair<std::int64_t, Vec3>>& sorted, std::int64_t id) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), id,
                                     [](const auto& entry, std::int64_t key) { return entry.first < key; });
    return it != sorted.end() && it->first == id ? &it->second : nullptr;
}
}  // namespace

void Neighbourhood::setup(const std::vector<std::unique_ptr<ForceTerm>>& terms) {
    double cutoff = 0;
    for (const auto& term : terms) cutoff = std::max(cutoff, term->cutoff());
    list_ = NeighbourList(cutoff, s_.settings.skin);
    set_pair_ranges(terms, cutoff);
    s_.grid->require_width(ghost_width());
    cells_.setup(s_.grid->lo(), s_.grid->hi(), ghost_width(), list_.list_cutoff(), s_.settings.cell_subdivisions);
}

/// The terms' ranges by species pair, the largest for each pair (symmetric, at most the cutoff),
/// set on the list where some pair's is shorter than the cutoff.
void Neighbourhood::set_pair_ranges(const std::vector<std::unique_ptr<ForceTerm>>& terms, double cutoff) {
    std::vector<std::vector<double>> tables;  // each term's, and its width
    std::vector<std::size_t> widths;
    std::size_t n = 0;
    for (const auto& term : terms) {
        tables.push_back(term->pair_ranges());
        const std::size_t size = tables.back().size(),
                          m = static_cast<std::size_t>(std::llround(std::sqrt(double(size))));
        if (m * m != size) throw std::logic_error("force term '" + term->name() + "': pair_ranges() is not n x n");
        widths.push_back(m);
        n = std::max(n, m);
    }
    if (n == 0) return;
    std::vector<double> range(n * n, 0.0);
    for (std::size_t t = 0; t < terms.size(); ++t) {
        const std::vector<double>& own = tables[t];
        const std::size_t m = widths[t];
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = 0; j < n; ++j) {
                const double r = i < m && j < m ? std::max(own[i * m + j], own[j * m + i]) : terms[t]->cutoff();
                range[i * n + j] = std::max(range[i * n + j], std::min(r, cutoff));
            }
    }
    if (std::all_of(range.begin(), range.end(), [&](double r) { return r >= cutoff; })) return;
    list_.set_pair_ranges(range, static_cast<int>(n));
}

void Neighbourhood::choose_layout(const std::vector<std::unique_ptr<ForceTerm>>& terms) {
    const ListLayout layout = s_.settings.list_layout;
    std::string host_only;
    for (const auto& term : terms)
        if (!term->on_backend() && host_only.empty()) host_only = term->name();
    if (layout == ListLayout::Full && !host_only.empty())
        throw InputError("neighbour_list=full: force term '" + host_only +
                         "' has no back-end form yet (use half or auto)");
    full_list_ = layout == ListLayout::Full ||
                 (layout == ListLayout::Auto && s_.settings.backend != Backend::Host && host_only.empty());
    // Wedge images and bodies' spheres may lie inside a domain as ghosts: no particle is sure to
    // be free of them, so nothing is ordered. Only for the overlap (or to check it): the order
    // takes some memory locality from the force loop and the list build, and on one node the
    // overlap gained nothing (benchmarks/results/scaling.md), so runs without it keep the cell order.
    interior_first_ = !s_.particles.mirrored() && !full_list_ && !s_.bodies() && !s_.box.wedge.active() &&
                      !terms.empty() && terms.front()->cutoff() > 0 && terms.front()->honours_range() &&
                      s_.grid->size() > 1 && (s_.settings.overlap_halo || s_.settings.interior_order);
    n_interior_ = 0;
}

/// The list where the back end reads it: uploaded after each build (host code builds it).
void Neighbourhood::place_full_list() {
    list_offset_ = list_.offsets();
    list_index_ = list_.neighbours();
    exec::ParticleMirror* mirror = s_.mirror();
    if (!mirror) return;
    list_offset_ = static_cast<const std::uint32_t*>(mirror->upload(
        EngineState::kListOffsets, list_.offsets(), (list_.n_owned() + 1) * sizeof(std::uint32_t)));
    list_index_ = static_cast<const std::uint32_t*>(
        mirror->upload(EngineState::kListIndex, list_.neighbours(), list_.n_pairs() * sizeof(std::uint32_t)));
}

const Vec3* Neighbourhood::check_origin() const {
    if (s_.mirror()) return reference_on_backend_;
    const std::vector<Vec3>& x0 = list_.reference_positions();
    return x0.size() == s_.store.n_owned() ? x0.data() : nullptr;
}

const std::vector<Vec3>& Neighbourhood::reference_positions() const {
    if (!built_on_backend_) return list_.reference_positions();
    if (!reference_copied_) {
        reference_copy_.resize(s_.store.n_owned());
        s_.mirror()->copy_to_host(reference_copy_.data(), reference_on_backend_, s_.store.n_owned() * sizeof(Vec3));
        reference_copied_ = true;
    }
    return reference_copy_;
}

/// The build where the particles live (BackendListBuild); false where it declined.
bool Neighbourhood::rebuild_where_particles_live() {
    if (!s_.boundaries.empty()) s_.agree_on_boundary_faults();
    BackendListBuild::Bodies body_tables;
    if (s_.bodies())
        body_tables = {&s_.rigid,
                       s_.bodies_resident.mirror(),
                       &s_.rigid.store(),
                       s_.frames_on_backend,
                       s_.frame_species_on_backend,
                       s_.frame_diameters_on_backend,
                       EngineState::kBodyFields};
    exec::ParticleMirror& mirror = *s_.mirror();
    const int n_species = list_.n_range_species();
    backend_build_.set_pair_ranges(
        n_species ? mirror.table(EngineState::kPairRangeTable, list_.range_table()) : nullptr, n_species);
    if (!backend_build_.build(s_.target, mirror, s_.store, *s_.grid, cells_, ghost_width(), list_.list_cutoff(),
                              halo_, backend_halo_, s_.bodies() ? &body_tables : nullptr))
        return false;
    if (!backend_build_.fault().empty()) throw InstabilityError(backend_build_.fault());
    s_.times.migrate += backend_build_.take_migration_seconds();
    backend_halo_.prepare(s_.target, halo_, mirror, EngineState::kHaloPack);
    list_offset_ = backend_build_.offsets();
    list_index_ = backend_build_.neighbours();
    reference_on_backend_ = backend_build_.reference();
    if (s_.bodies()) s_.constituents_on_backend = backend_build_.constituents();
    built_on_backend_ = true;
    reference_copied_ = false;
    moved_since_build_ = false;
    ++rebuilds_;
    check_count();
    return true;
}

void Neighbourhood::rebuild(bool on_backend) {
    const exec::Transfers before = exec::transfers();
    ++build_serial_;
    build(on_backend);
    keep_most(s_.ledger.list_build, work_since(before));
    ++s_.ledger.builds;
}

void Neighbourhood::build(bool on_backend) {
    PhaseTimer timer(s_.times.neighbour);
    drift_moved_known_ = false;
    if (on_backend && s_.mirror() && full_list_ && rebuild_where_particles_live()) return;
    built_on_backend_ = false;
    ParticleStore& store = s_.store;
    // Host code (decomposition, cells, list) that reorders and resizes every array; forces are
    // recomputed after it.
    s_.particles.host_reads(kAllFields & ~kForce);
    s_.particles.host_wrote(kAllFields);
    if (!s_.boundaries.empty()) s_.agree_on_boundary_faults();
    // Bodies migrate and place their constituents (host code).
    s_.bodies_resident.host_reads(EngineState::kBodyFields);
    s_.bodies_resident.host_wrote(EngineState::kBodyFields);
    if (s_.bodies()) s_.rigid.drop_constituents(store);
    {
        PhaseTimer migrating(s_.times.migrate);
        migration_.apply(store, *s_.grid);
        // Bodies move whole, by their centre of mass; their spheres follow.
        if (s_.bodies() && !bodies_dealt_) s_.rigid.migrate(*s_.grid);
        bodies_dealt_ = false;
    }
    if (s_.bodies()) s_.rigid.append_constituents(store);
    if (!restored_reference_.empty()) {
        // Spheres come with their bodies (io::restore_checkpoint deals them so); one that did
        // not is binned at its body's pose.
        for (std::size_t i = 0; i < store.n_owned(); ++i)
            if (const Vec3* at = s_.is_free(i) ? nullptr : find_by_id(restored_reference_, store.id[i]))
                store.position[i] = *at;
        std::vector<std::pair<std::int64_t, Vec3>>().swap(restored_reference_);
    }
    // Cell order gives the force loop neighbours that sit close in memory.
    cells_.sort_order(store.position.data(), store.id.data(), store.n_owned(), order_);
    if (interior_first_) order_interior_first();
    store.permute_owned(order_, kAllFields & ~kForce);  // forces are recomputed after a build
    halo_.build(store, *s_.grid, ghost_width(), s_.ghost_fields);
    cells_.bin_after_sort(store.position.data(), store.size());
    // Wedge images turned by other than a quarter or half turn land inside the domain's cells,
    // so the search cannot assume those hold owned particles only.
    const bool mixed_cells = s_.bodies() || (s_.box.wedge.active() && s_.box.wedge.n != 2 && s_.box.wedge.n != 4);
    if (full_list_) {
        list_.build_full(store, cells_);
        place_full_list();
    } else {
        list_.build(store, cells_, mixed_cells);
        if (interior_first_) check_interior();
    }
    moved_since_build_ = false;
    if (exec::ParticleMirror* mirror = s_.mirror()) {
        const std::vector<Vec3>& reference = list_.reference_positions();
        reference_on_backend_ = static_cast<const Vec3*>(
            mirror->upload(EngineState::kReference, reference.data(), reference.size() * sizeof(Vec3)));
        backend_halo_.place(halo_, *mirror, EngineState::kHaloIndex);
        backend_halo_.prepare(s_.target, halo_, *mirror, EngineState::kHaloPack);
    }
    if (s_.bodies()) {
        s_.rigid.index_constituents(store);
        s_.place_constituents();
    }
    ++rebuilds_;
    check_count();
}

const std::vector<std::uint32_t>& Neighbourhood::particle_costs() const {
    const std::size_t n = s_.store.n_owned();
    const std::uint32_t* offset = list_.offsets();
    if (built_on_backend_) {
        offset_copy_.resize(n + 1);
        s_.mirror()->copy_to_host(offset_copy_.data(), backend_build_.offsets(), (n + 1) * sizeof(std::uint32_t));
        offset = offset_copy_.data();
    } else if (list_.n_owned() != n) {
        throw std::logic_error("particle_costs: the list does not match the particles");
    }
    cost_scratch_.resize(n);
    for (std::size_t i = 0; i < n; ++i) cost_scratch_[i] = offset[i + 1] - offset[i] + decomp::kParticleCost;
    return cost_scratch_;
}

bool Neighbourhood::rebalance() {
    PhaseTimer timer(s_.times.neighbour);
    s_.particles.host_reads(kPosition);
    const std::vector<std::uint32_t>& cost = particle_costs();
    // Particles may be up to about half the skin outside their domain when a build is due:
    // planes stay a skin inside the neighbouring domains, so one migration pass suffices.
    const decomp::BalanceReport report = decomp::balance_cuts(
        *s_.grid, s_.store.position.data(), cost.data(), s_.store.n_owned(), ghost_width(), s_.settings.skin);
    if (balance_stats_.rebalances == 0) balance_stats_.imbalance_first = report.imbalance_before;
    balance_stats_.imbalance_last = report.imbalance_before;
    ++balance_stats_.rebalances;
    if (report.axes_moved == 0) return false;
    cells_.setup(s_.grid->lo(), s_.grid->hi(), ghost_width(), list_.list_cutoff(), s_.settings.cell_subdivisions);
    return true;
}

/// Puts first, in the order, the owned particles farther than the list range from every face
/// that brings ghosts (a neighbour's, or the rank's own periodic images): no ghost can be in
/// their rows of the list. Each part keeps its cell order.
void Neighbourhood::order_interior_first() {
    const decomp::RankGrid& grid = *s_.grid;
    const Vec3 lo = grid.lo(), hi = grid.hi();
    // The search's range, widened as its single-precision copy widens it (NeighbourList).
    const double range = list_.list_cutoff() + cells_.binned_distance_error();
    bool low[3], high[3];
    for (int d = 0; d < 3; ++d) {
        low[d] = grid.neighbour(d, 0) != MPI_PROC_NULL;
        high[d] = grid.neighbour(d, 1) != MPI_PROC_NULL;
    }
    n_interior_ = cells_.partition_sorted(order_, [&](std::uint32_t i) {
        const Vec3& x = s_.store.position[i];
        for (int d = 0; d < 3; ++d)
            if ((low[d] && x[d] - lo[d] <= range) || (high[d] && hi[d] - x[d] <= range)) return false;
        return true;
    });
}

/// The rows of the interior particles hold no ghost (what the overlap relies on).
void Neighbourhood::check_interior() const {
    const std::uint32_t *offset = list_.offsets(), *nb = list_.neighbours();
    const std::size_t n_owned = s_.store.n_owned();
    for (std::uint32_t k = 0; k < offset[n_interior_]; ++k)
        if (nb[k] >= n_owned) throw std::logic_error("an interior particle has a ghost in its list row");
}

/// After a build: no particle was lost or made on the way. Collective.
void Neighbourhood::check_count() const {
    const long long n = decomp::sum(s_.comm, static_cast<long long>(s_.store.n_owned()));
    if (n != s_.n_global) {
        std::ostringstream msg;
        msg << "particle count changed from " << s_.n_global << " to " << n << " at step " << s_.step;
        throw InstabilityError(msg.str());
    }
}

double Neighbourhood::local_moved_sq() {
    PhaseTimer timer(s_.times.communicate);
    if (drift_moved_known_) {
        drift_moved_known_ = false;
        return drift_moved_sq_;
    }
    if (exec::ParticleMirror* mirror = s_.mirror()) {
        s_.particles.backend_reads(kPosition);
        return exec::transform_max(s_.target, s_.store.n_owned(), 0.0,
                                   SquaredDisplacement{mirror->array<Vec3>(kPosition), reference_on_backend_});
    }
    return list_.max_displacement_sq(s_.store);
}

void Neighbourhood::reduce_vote(double* values, int n) {
    PhaseTimer timer(s_.times.communicate);
    PhaseTimer voting(s_.times.collective_wait, s_.after_build_slot());
    decomp::max_then_sum_in_place(s_.comm, values, n);
}

bool Neighbourhood::decide(double moved_sq) {
    bool needed = list_.rebuild_due(moved_sq);
    if (balance_due_) {
        balance_due_ = false;
        if (rebalance()) needed = true;
    }
    return needed;
}

void Neighbourhood::follow(bool build, bool defer) {
    if (build) {
        built_this_step_ = true;
        rebuild(true);
        s_.sum_after_build_pending = true;
        return;
    }
    refresh_ghosts(defer);
}

/// The ghosts follow their owners: positions, and velocities where contact forces with damping
/// or friction need their partners'.
void Neighbourhood::refresh_ghosts(bool defer) {
    PhaseTimer timer(s_.times.communicate);
    ParticleStore& store = s_.store;
    if (exec::ParticleMirror* mirror = s_.mirror()) {
        backend_halo_.gather(s_.target, halo_, *mirror, mirror->array<Vec3>(kPosition), true, EngineState::kHaloPack);
        s_.particles.backend_wrote(kPosition);
        if (s_.ghost_fields & kVelocity) {
            s_.particles.backend_reads(kVelocity);
            backend_halo_.gather(s_.target, halo_, *mirror, mirror->array<Vec3>(kVelocity), false,
                                 EngineState::kHaloPack);
            s_.particles.backend_wrote(kVelocity);
        }
    } else if (defer && overlap_now()) {
        halo_.begin_refresh(store, (s_.ghost_fields & kVelocity) != 0);
        refresh_in_flight_ = true;
    } else {
        halo_.gather_positions(store);
        if (s_.ghost_fields & kVelocity) halo_.gather_velocities(store);
    }
}

void Neighbourhood::gather_on_host() {
    halo_.gather_positions(s_.store);
    if (s_.ghost_fields & kVelocity) halo_.gather_velocities(s_.store);
}

MessageTraffic Neighbourhood::traffic() const {
    MessageTraffic t;
    t.ghost_refresh = halo_.refresh_traffic();
    t.ghost_build = halo_.build_traffic();
    t.ghost_build += backend_build_.ghost_traffic();
    t.migration = migration_.traffic();
    t.migration += backend_build_.migration_traffic();
    return t;
}

}  // namespace emergent
