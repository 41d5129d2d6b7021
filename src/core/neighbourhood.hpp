// SPDX-License-Identifier: MIT
// Who is near whom, and who owns whom: the cells, the Verlet list, the halo of ghosts and the
// migration between ranks, on the host or where the particles live (BackendListBuild). It
// decides when the list is rebuilt (half the skin moved) and when the domains are rebalanced,
// and keeps the ghosts following their owners between builds.
#pragma once
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/engine_state.hpp"
#include "decomposition/halo_exchange.hpp"
#include "decomposition/migration.hpp"
#include "emergent/force_term.hpp"
#include "neighbour/backend_halo.hpp"
#include "neighbour/backend_list_build.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

class Neighbourhood {
public:
    explicit Neighbourhood(EngineState& state) : s_(state) {}

    /// The list and cells for the force terms present (their longest cutoff, their ranges by
    /// species pair).
    void setup(const std::vector<std::unique_ptr<ForceTerm>>& terms);
    /// Half list (host code) or full list (the back end's force loops), and whether owned
    /// particles are ordered interior first for the halo overlap.
    void choose_layout(const std::vector<std::unique_ptr<ForceTerm>>& terms);

    /// Re-partitions particles and rebuilds ghosts, cells and the Verlet list. `on_backend`:
    /// the build may run where the particles live (on one rank it moves no particle array);
    /// the host builds for the half list, at initialise and restore, and where the back end
    /// declines (ids beyond its 32-bit sort keys). Collective.
    void rebuild(bool on_backend = false);
    /// Moves the planes between domains to equal shares of the work (LoadBalance::Cost); where
    /// they moved (returns true) a build must follow. Collective.
    bool rebalance();
    /// After a drift, the step's one collective in three parts. This rank's largest squared
    /// displacement since the last build (taken in the drift's pass, or measured now).
    double local_moved_sq();
    /// `values` over all ranks in one reduction, in place: the first decomp::kVoteMaxima as
    /// maxima (the displacement, and what else bounds it), the rest summed (the thermostat's).
    void reduce_vote(double* values, int n);
    /// Whether the list must be rebuilt, from the largest squared displacement over the ranks
    /// (or a bound on it): beyond half the skin, or the planes move. Throws InstabilityError
    /// where a particle ran away (not finite, or beyond cutoff + skin).
    bool decide(double moved_sq);
    /// Then the list is rebuilt (`build`: what decide() said), or the ghosts follow their owners.
    /// `defer`: the forces that follow are not sampled, so the ghosts' refresh may overlap them.
    void follow(bool build, bool defer);

    /// Where the rebuild test's origin (the owned positions at the last build) lies in the
    /// memory the loops run on; null where it does not match the owned particles.
    const Vec3* check_origin() const;
    /// The drift's pass took the largest squared displacement since the last build.
    void drift_moved(double moved_sq) {
        drift_moved_sq_ = moved_sq;
        drift_moved_known_ = true;
    }
    void note_moved() { moved_since_build_ = true; }
    bool moved_since_build() const { return moved_since_build_; }
    /// Owned positions at the last list build (the displacement check's origin), on the host.
    const std::vector<Vec3>& reference_positions() const;
    /// Each owned particle's work: its entries in the list last built plus the fixed share.
    const std::vector<std::uint32_t>& particle_costs() const;

    /// The same on every rank (the refresh's messages must match), even where a rank has no
    /// interior particle.
    bool overlap_now() const { return interior_first_ && s_.settings.overlap_halo; }
    bool interior_first() const { return interior_first_; }
    std::size_t n_interior() const { return n_interior_; }
    bool full_list() const { return full_list_; }
    /// The full list where the back end reads it.
    const std::uint32_t* list_offset() const { return list_offset_; }
    const std::uint32_t* list_index() const { return list_index_; }
    const NeighbourList& list() const { return list_; }
    /// The half list's force loops with the ghosts' refresh in flight (overlap_now()): they
    /// advance it between their shares of the interior rows and end it.
    decomp::HaloExchange& halo() { return halo_; }
    const decomp::HaloExchange& halo() const { return halo_; }
    bool refresh_in_flight() const { return refresh_in_flight_; }
    void refresh_done() { refresh_in_flight_ = false; }

    double ghost_width() const { return s_.ghost_width(list_.list_cutoff()); }
    long long rebuilds() const { return rebuilds_; }
    /// Counts every build of this object (never set back, unlike rebuilds()).
    unsigned long long build_serial() const { return build_serial_; }
    void set_rebuilds(long long n) { rebuilds_ = n; }
    /// The step rebuilt the list.
    bool built_this_step() const { return built_this_step_; }
    void begin_step(bool balance_due) {
        built_this_step_ = false;
        balance_due_ = balance_due;
    }
    const LoadBalanceStats& balance_stats() const { return balance_stats_; }
    /// Messages sent by the builds, refreshes and migrations so far.
    MessageTraffic traffic() const;

    /// A restore's one build: the saved list-reference positions by id (sorted), where bodies'
    /// spheres are binned (where the run's last build binned them, not at their bodies' current
    /// poses, so the list and the force sums' order are the run's); and the bodies stay on the
    /// ranks they were dealt to (as they would have in the uninterrupted run) until the next.
    void restore_bodies_at(std::vector<std::pair<std::int64_t, Vec3>> reference) {
        restored_reference_ = std::move(reference);
        bodies_dealt_ = true;
    }
    /// The ghosts' positions (and velocities where the terms read them) from their owners, on
    /// the host.
    void gather_on_host();

private:
    /// rebuild() less the ledger's count.
    void build(bool on_backend);
    void set_pair_ranges(const std::vector<std::unique_ptr<ForceTerm>>& terms, double cutoff);
    bool rebuild_where_particles_live();
    void place_full_list();
    void order_interior_first();
    void check_interior() const;
    void check_count() const;
    void refresh_ghosts(bool defer);

    EngineState& s_;
    decomp::Migration migration_;
    decomp::HaloExchange halo_;
    CellList cells_;
    NeighbourList list_;
    std::vector<std::uint32_t> order_;
    long long rebuilds_ = 0;
    unsigned long long build_serial_ = 0;
    bool moved_since_build_ = true;  ///< a drift since the last list build
    std::vector<std::pair<std::int64_t, Vec3>> restored_reference_;
    bool bodies_dealt_ = false;
    bool built_this_step_ = false;
    bool balance_due_ = false;  ///< the planes move at this step's next drift
    double drift_moved_sq_ = 0;
    bool drift_moved_known_ = false;
    /// Ghost refresh overlapped with the pair forces. Where the run allows it, the owned
    /// particles are ordered with the n_interior whose list rows need no ghost first, whether
    /// or not the overlap is switched on, so that on and off give the same bits.
    bool interior_first_ = false;
    std::size_t n_interior_ = 0;
    bool refresh_in_flight_ = false;
    LoadBalanceStats balance_stats_;
    mutable std::vector<std::uint32_t> cost_scratch_, offset_copy_;
    bool full_list_ = false;
    const std::uint32_t *list_offset_ = nullptr, *list_index_ = nullptr;
    /// With a mirror, the rebuild test and the ghosts' positions run on the back end too.
    exec::BackendHalo backend_halo_;
    const Vec3* reference_on_backend_ = nullptr;  ///< positions at the last list build
    /// List builds where the particles live (one rank without bodies), and whether the last
    /// build was one: then the host's copy of its reference positions is made on demand.
    BackendListBuild backend_build_;
    bool built_on_backend_ = false;
    mutable bool reference_copied_ = false;
    mutable std::vector<Vec3> reference_copy_;
};

}  // namespace emergent
