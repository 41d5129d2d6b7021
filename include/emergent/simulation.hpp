// SPDX-License-Identifier: MIT
// One decomposed particle system and its time step: what scenes compose and the engine runs.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "emergent/boundary.hpp"
#include "emergent/box.hpp"
#include "emergent/field_grid.hpp"
#include "emergent/force_term.hpp"
#include "emergent/message_counts.hpp"
#include "emergent/particle_store.hpp"
#include "emergent/thermostat.hpp"
#include "emergent/wall_layer.hpp"

namespace emergent {

/// Engine settings a scene does not choose (they come from the run parameters).
/// How a time step is split into kicks (v += h f/m) and drifts (x += h v). Both are
/// symplectic, time-reversible and of second order.
enum class Integrator {
    /// kick dt/2, drift dt, kick dt/2: one force evaluation per step.
    VelocityVerlet,
    /// Omelyan, Mryglod & Folk (2002), the velocity form of their second-order minimum-error
    /// scheme: kick l dt, drift dt/2, kick (1 - 2l) dt, drift dt/2, kick l dt with
    /// l = 0.1932. Two force evaluations per step for a leading error about ten times smaller
    /// than velocity Verlet's (it pays where accuracy at a given cost matters more than steps).
    Omelyan,
};

/// Where a run's particle data live and its per-particle loops run (run parameter `backend`).
enum class Backend {
    /// CPU loops on the particle store itself.
    Host,
    /// The host back end run as a device would be: particle data kept in memory apart from the
    /// store, copied only where the step syncs, and the store's copy of a field poisoned (NaN,
    /// large negative integers) while its current values are elsewhere. Bitwise the results of
    /// Host; for tests (a missing sync shows on a CPU) and for counting transfers.
    Checking,
    /// A CUDA device, one per rank.
    Cuda,
};

/// How the neighbour list is laid out (run parameter `neighbour_list`).
/// Messages between ranks straight from and into the back end's memory (RunSettings::mpi_direct).
enum class MpiDirect {
    Auto,  ///< where the MPI library reports that it reads CUDA device memory
    On,    ///< always (a CUDA-aware MPI the query misses; the checking back end's test of the path)
    Off,   ///< always staged through host memory
};

enum class ListLayout {
    /// Half on the host back end, full on the others (when every force term has a back-end form).
    Auto,
    /// Each pair once, forces on both members (Newton's third law): the host's fastest.
    Half,
    /// Each pair under both members, each particle summing its own force: the layout a device
    /// needs, run on the host to check the device's loops bitwise against the checking back end.
    Full,
};

/// How the planes cutting the box into rank domains are placed (run parameter `balance`).
enum class LoadBalance {
    /// Equal slabs along each split axis, for the whole run.
    None,
    /// Planes moved so that every slab of ranks holds an equal share of the work, counted as
    /// neighbour-list entries plus a fixed share per particle (decomposition/load_balance.hpp):
    /// at initialise and at every `balance_every`-th step (0: at initialise only). The cost is
    /// an integer count, so a run is as reproducible as with None, and the planes are kept in
    /// snapshots and checkpoints, so a continuation on the same rank count stays exact.
    Cost,
};

struct RunSettings {
    double dt = 0.005;
    double skin = 0.3;
    /// Cells per neighbour-list range along each axis (finer cells: fewer candidate pairs).
    int cell_subdivisions = 1;
    Integrator integrator = Integrator::VelocityVerlet;
    Int3 grid{0, 0, 0};  ///< ranks per axis; 0 = choose
    Backend backend = Backend::Host;
    MpiDirect mpi_direct = MpiDirect::Auto;
    ListLayout list_layout = ListLayout::Auto;
    LoadBalance balance = LoadBalance::None;
    long long balance_every = 0;  ///< steps between rebalances with LoadBalance::Cost; 0: start only
    /// Steps before the measured phase (run parameter `equilibration_steps`).
    long long equilibration_steps = 0;
    /// Refresh ghosts while computing the pair forces that need none (Simulation::halo_overlap()
    /// says where it applies). It orders the owned particles interior first, so its results
    /// are round-off apart from those without (the same bits as without it but in that order).
    bool overlap_halo = false;
    /// Order the owned particles interior first without the overlap (halo_overlap=ordered):
    /// the overlap's order with a blocking refresh, bit for bit the overlapped run.
    bool interior_order = false;
};

/// What load balancing did so far (Simulation::load_balance()), the same on every rank.
struct LoadBalanceStats {
    long long rebalances = 0;      ///< times the planes were placed (initialise included)
    double imbalance_first = 1;    ///< max/mean rank cost before the first placement
    double imbalance_last = 1;     ///< max/mean rank cost before the latest placement
};

/// Bounds of the run-time guards; 0 switches a bound off.
struct GuardLimits {
    double max_force = 0;  ///< largest |f| on any particle (overlaps show up here first)
};

/// Everything needed to continue from one step: this rank's owned particles and the positions
/// the neighbour list was built from.
/// Fields that hold one value for every particle (species 0, diameter 1) and forces that can be
/// recomputed are left out, and `reference` is empty when the list was built at the saved step
/// (the positions are the reference): a kept state of a one-species fluid costs 88 bytes per
/// particle, 64 at a list build.
struct StateSnapshot {
    ParticleStore owned;
    std::vector<Vec3> reference;  ///< empty: the positions themselves
    ParticleStore bodies;  ///< rigid bodies owned here (empty without bodies)
    std::vector<double> domain_cuts;  ///< Simulation::domain_cuts() at the snapshot
    long long step = 0, rebuilds = 0;
    double time = 0;
};

/// Global thermodynamic state at one step; energies are per particle.
struct ThermoSample {
    long long step = 0;
    double time = 0;
    long long n = 0;
    double kinetic = 0, potential = 0, total = 0;
    double temperature = 0, pressure = 0;
    Vec3 momentum{0, 0, 0};
    Vec3 angular_momentum{0, 0, 0};  ///< about the origin, from unwrapped positions
    /// Largest granular overlap / sphere diameter at the last sampling step; -1 without contacts.
    double max_overlap = -1;
};

/// Kinetic energy by kind of motion, summed over all ranks: free particles, and rigid bodies'
/// translation and rotation. With the degrees of freedom of each (3 per free particle, 3 + 3
/// per body) it gives their separate temperatures.
struct KineticParts {
    double free = 0, translational = 0, rotational = 0;
    long long n_free = 0, n_bodies = 0;
};

/// Langevin dynamics for rigid bodies, an implicit solvent: at the end of every step each
/// body's velocity relaxes at `translation_rate` (friction force -rate M v) and its angular
/// velocity about each principal axis at `rotation_rate` (torque -rate I w), with the noise that
/// keeps them at `temperature` (the exact Ornstein-Uhlenbeck update, noise drawn from (seed,
/// body id, step): the same on any rank count). Diffusion: D = T / (M rate) in translation,
/// T / (I_k rate) about principal axis k.
struct BodyLangevinSettings {
    double temperature = 1, translation_rate = 0, rotation_rate = 0;
    std::uint64_t seed = 0;
};

/// Wall-clock seconds spent in each part of the step (this rank).
struct PhaseTimes {
    double neighbour = 0;  ///< migration, sorting, ghost build, cell and Verlet lists
    double migrate = 0;    ///< of `neighbour`: particles and bodies moved to their new owners
    double force = 0;
    double integrate = 0;  ///< both half steps and the thermostat
    double communicate = 0;  ///< ghost position refresh and the rebuild check
    /// Blocked waiting for ghost data in refreshes (inside `communicate`, or inside `force`
    /// where the refresh overlaps the forces).
    double halo_wait = 0;
    /// In the step's global reductions (the rebuild vote, inside `communicate`; the
    /// thermostat's kinetic energy, inside `integrate`): mostly waiting for the slowest rank.
    double collective_wait = 0;
    /// Of `collective_wait`: the thermostat's sum in steps that rebuilt the list, where the
    /// ranks' list builds (the step's largest work) meet.
    double collective_wait_after_build = 0;
};

/// The work of one step or one list build on this rank, as the step ledger counts it
/// (exec::Transfers): passes over particles (kernel launches on a device), results read back to
/// the host, collective operations across ranks, arrays and their bytes moved between the host
/// and the back end.
struct StepWork {
    std::uint64_t passes = 0, read_backs = 0, collectives = 0, arrays = 0, array_bytes = 0;
};

/// The step ledger: the most work any one step of each kind took since reset_phase_times(),
/// as a budget (tests hold it): plain steps (no build, no sampling), sampled steps (energy and
/// virial, no build), and list builds by themselves (the build inside a step; a step that
/// builds is counted there only).
struct StepLedger {
    StepWork plain_step, sampled_step, list_build;
    long long plain_steps = 0, sampled_steps = 0, builds = 0;
};

/// A particle system decomposed over the ranks of a communicator.
///
/// A scene sets the box, species masses, force terms, thermostat and particles; then
/// initialise() and step() run it. Particles are added with global coordinates by every rank;
/// each rank keeps those inside its own domain.
class Simulation {
public:
    Simulation(MPI_Comm comm, const RunSettings& settings);
    ~Simulation();
    Simulation(const Simulation&) = delete;
    Simulation& operator=(const Simulation&) = delete;

    // --- composition (before initialise) ---
    /// Sets the region and partitions it; split_axis[d] = false keeps axis d on one rank.
    /// A wedge region (box.wedge) needs x and y bounded; they are then never split.
    void set_box(const Box& box, const bool split_axis[3] = nullptr);
    /// Mass per species; 0 makes a species of points without inertia (attraction sites),
    /// allowed only as constituents of rigid bodies.
    void set_species_masses(const std::vector<double>& masses);
    void add_force(std::unique_ptr<ForceTerm> term);
    /// A global thermostat. With rigid bodies it acts on the free particles alone (an explicit
    /// solvent bath), rescaling their velocities about their mean; the bodies reach the bath's
    /// temperature through collisions only.
    void set_thermostat(std::unique_ptr<Thermostat> thermostat);
    /// Langevin dynamics for the rigid bodies (after the thermostat, if any, in each step).
    void set_body_langevin(const BodyLangevinSettings& settings);
    /// Adds a boundary rule (applied after each drift, in the order added); the simulation
    /// keeps it, the scene may keep the returned pointer to read the rule's exchange.
    BoundaryRule* add_boundary(std::unique_ptr<BoundaryRule> rule);
    /// The boundary rules, in the order added.
    std::vector<const BoundaryRule*> boundary_rules() const;
    /// Adds a wall-layer thermostat (applied at the end of each step, after the global
    /// thermostat); the simulation keeps it, the scene may read its energy through the pointer.
    WallLayerThermostat* add_wall_layer(std::unique_ptr<WallLayerThermostat> layer);
    /// A rule's exchange summed over all ranks. Collective.
    WallExchange global_exchange(const BoundaryRule& rule) const;
    /// Every boundary rule's global exchange (hits, momentum x y z, angular momentum, energy)
    /// and every wall layer's energy, flattened in the order added: what a checkpoint keeps so
    /// that a continued run's tallies go on from where they were. Collective.
    std::vector<double> exchange_tallies() const;
    /// Sets the tallies from exchange_tallies() of the same scene (rank 0 holds the global
    /// sums, other ranks zero). InputError if the layout does not match.
    void restore_exchange_tallies(const std::vector<double>& tallies);
    /// Keeps the particle if x lies in this rank's domain.
    void add_particle(const Vec3& x, const Vec3& v, int species, std::int64_t id,
                      double diameter = 1.0);
    /// Declares a kind of rigid body: spheres of the given species and diameters at the given
    /// positions (any frame; mass, centre and principal axes follow from the spheres). Called
    /// identically on every rank; returns the kind's index.
    int add_body_kind(const std::vector<Vec3>& positions, const std::vector<int>& species,
                      const std::vector<double>& diameters);
    /// Adds a rigid body if its centre of mass lies in this rank's domain. `orientation`
    /// rotates the frame the kind's spheres were given in into space (the identity: as
    /// given); `omega` is the angular velocity (space frame). Its spheres get particle ids
    /// first_particle_id, first_particle_id + 1, ...
    void add_body(int kind, const Vec3& com, const Quat& orientation, const Vec3& velocity,
                  const Vec3& omega, std::int64_t id, std::int64_t first_particle_id);
    bool has_bodies() const;
    /// This rank's rigid bodies (position = centre of mass, orientation, ...); empty if none.
    /// As particles(): the non-const form counts every body field as changed by the caller (the
    /// back end's copy is sent again before the next step), the const form only reads; a
    /// scene that only reads calls the const form (std::as_const(sim).bodies()).
    ParticleStore& bodies();
    const ParticleStore& bodies() const;
    long long n_bodies_global() const;
    /// Sets velocities from a Maxwell distribution at temperature T (same for any rank
    /// count), with zero total momentum and the kinetic energy of exactly T.
    void assign_thermal_velocities(double temperature, std::uint64_t seed);

    // --- running ---
    /// Decomposes, builds ghosts and lists, and computes the first forces.
    void initialise();
    /// One velocity-Verlet step; `sample` makes the force terms also sum energy and virial,
    /// which measure() then reports.
    void step(bool sample);
    /// Global thermodynamic state; potential energy and pressure refer to the last step taken
    /// with sample = true (or to initialise()).
    ThermoSample measure() const;
    /// Kinetic energy of free particles and of bodies' translation and rotation. Collective.
    KineticParts kinetic_parts() const;

    // --- guards ---
    /// Checks that every position, velocity and force is finite and within `limits`; throws
    /// InstabilityError on every rank, naming the first offending particle. Collective.
    void check_guards(const GuardLimits& limits) const;

    // --- checkpoints ---
    /// A copy of the current state (owned particles only; cheap next to a step).
    StateSnapshot snapshot() const;
    /// The same into an existing snapshot, reusing its memory (no second copy at the peak).
    void snapshot(StateSnapshot& into) const;
    /// Returns to a snapshot taken earlier on the same ranks.
    void restore(const StateSnapshot& snapshot);
    /// Owned positions at the last neighbour-list build, in the order of particles().
    const std::vector<Vec3>& list_reference_positions() const;
    /// Rank whose domain holds x (after set_box).
    int rank_of(const Vec3& x) const;
    /// The planes cutting the box into rank domains: dims.x + 1 along x (from box lo to hi),
    /// then dims.y + 1 along y, dims.z + 1 along z (see rank_grid_dims()).
    std::vector<double> domain_cuts() const;
    /// Places the planes as domain_cuts() returned them on the same rank grid, before
    /// restore() or initialise(); InputError where they do not fit this grid and box.
    void set_domain_cuts(const std::vector<double>& planes);
    /// Rebalances so far and the cost imbalance they found (LoadBalance::Cost).
    const LoadBalanceStats& load_balance() const;
    /// Max over ranks of the ranks' work / the mean (1: perfect), counted as LoadBalance::Cost
    /// counts it, from the list last built. Collective.
    double cost_imbalance() const;
    /// True when the ghost refresh overlaps the pair forces (RunSettings::overlap_halo, and
    /// the run allows it: the host builds a half list, the first force term is a pair term
    /// that honours row ranges, no rigid bodies or wedge images, more than one rank).
    bool halo_overlap() const;
    /// Of this rank's owned particles, the fraction whose list rows need no ghost (computed
    /// first while ghosts are in flight), from the last build; 0 without halo_overlap().
    double interior_fraction() const;
    /// Continues a saved run instead of initialise(): `owned` holds this rank's particles,
    /// `reference` their positions at the last list build (each particle must lie, at its
    /// reference position, in this rank's domain). The list is rebuilt exactly as it was built
    /// then, so a run continued on the same rank count retraces the original bit for bit.
    /// With rigid bodies, `bodies` holds this rank's bodies (by centre of mass); the spheres
    /// of bodies in `owned` are dropped and placed again from the bodies, so such a
    /// continuation may differ from the uninterrupted run by summation order (the list is
    /// built afresh; tests/io/rigid_output.sh finds a settling bed bit-identical).
    /// `saved_forces`: owned.force holds the forces of the saved step, which the run continues
    /// with (velocity-dependent forces cannot be recomputed from a saved state); otherwise they
    /// are recomputed from the positions. InputError (on every rank) where a body's spheres
    /// are not all in `owned` on the body's rank, or a body's kind is not declared.
    void restore(ParticleStore&& owned, std::vector<Vec3>&& reference, long long step,
                 double time, long long rebuilds, ParticleStore* bodies = nullptr,
                 bool saved_forces = false);

    // --- state ---
    /// This rank's particles, brought up to date from the back end (a sync: call it at
    /// sampling, output and checkpoints, not every step). The non-const form also counts every
    /// field as changed by the caller, so the back end gets them all again before the next step.
    ParticleStore& particles();
    const ParticleStore& particles() const;
    const Box& box() const;
    MPI_Comm comm() const;
    int rank() const;
    int n_ranks() const;
    Int3 rank_grid_dims() const;
    long long n_global() const;
    long long step_index() const;
    double time() const;
    double dt() const;
    // What a scene asks of time and range, instead of reading the engine's settings.
    /// The time the measured phase begins (equilibration_steps x dt): scenes average from here.
    double measurement_start() const;
    /// The steps that make up `duration` (at least one): a scene's period is a time, so its
    /// schedule does not change with dt.
    long long steps_in(double duration) const;
    /// How far the neighbour list reaches: the longest cutoff of the force terms added so far
    /// plus the skin. Ghost images and wedges must cover it.
    double interaction_range() const;
    long long rebuilds() const;
    double degrees_of_freedom() const;
    const std::vector<double>& species_masses() const;
    /// This instant's sums over the owned particles in each cell of `grid` (6 per cell: count,
    /// mass, momentum along the grid's axes, m v^2), positions folded into the box along its
    /// periodic axes: one sample of the coarse-grained fields. Made where the particles live
    /// (from a back end only the sums come back), with the same bits on every back end.
    std::vector<double> field_sums(const FieldGeometry& grid) const;
    bool has_thermostat() const;
    /// Where the particle data live and the loops run.
    Backend backend() const;
    /// True when total energy should be conserved: no thermostat, every force term conservative.
    bool conserves_energy() const;
    const PhaseTimes& phase_times() const;
    /// Point-to-point messages and bytes this rank sent to other ranks since the last
    /// reset_phase_times(), by purpose (ghost refresh, ghost build, migration); collectives
    /// (the rebuild vote, sums) are not counted. What the communication model is checked against.
    MessageTraffic message_traffic() const;
    /// Zeroes phase_times(), message_traffic() and step_ledger(): the measured phase starts.
    void reset_phase_times();
    /// The most work a step of each kind took on this rank since reset_phase_times().
    const StepLedger& step_ledger() const;

private:
    struct Engine;
    std::unique_ptr<Engine> engine_;
};

}  // namespace emergent
