// SPDX-License-Identifier: MIT
// The time step, the set-up of a run, and what a scene asks of the engine. The parts live in
// their own files: Neighbourhood (cells, list, halo, migration, balance), ForceEvaluation,
// Integration; measurement.cpp and state_restore.cpp hold Simulation's measures and its
// snapshot and restore.
#include "emergent/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/engine.hpp"
#include "decomposition/exact_sum.hpp"
#include "decomposition/load_balance.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "emergent/gpu.hpp"
#include "emergent/random.hpp"

namespace emergent {

void Simulation::Engine::prepare() {
    require_grid("initialise");
    particles.host_reads(kAllFields);  // the store's arrays are refitted below
    particles.host_wrote(kAllFields);
    neighbourhood.setup(forces.terms());
    if (bodies() && !motion.wall_layers.empty())
        throw InputError("wall-layer thermostats act on free particles only");
    if (bodies() && !boundaries.empty())
        throw InputError("boundary rules (hard walls) act on free particles only; rigid "
                         "bodies need force walls");
    if (bodies() && box.wedge.active())
        throw InputError("rigid bodies in a wedge region are not supported");
    n_global = decomp::sum(comm, static_cast<long long>(store.n_owned()));
    if (particle_fields & kDiameter) store.enable_diameters();  // contacts read them
    store.fit_capacity();
    neighbourhood.choose_layout(forces.terms());
}

Simulation::Simulation(MPI_Comm comm, const RunSettings& settings)
    : engine_(std::make_unique<Engine>()) {
    engine_->comm = comm;
    engine_->settings = settings;
    switch (settings.backend) {
    case Backend::Host:
        break;
    case Backend::Checking:
        engine_->particles.keep_mirror(std::make_unique<exec::ParticleMirror>(exec::separate_host_memory(), true));
        engine_->bodies_resident.keep_mirror(
            std::make_unique<exec::ParticleMirror>(exec::separate_host_memory(), true));
        engine_->target.separate = true;
        engine_->target.direct_mpi = settings.mpi_direct == MpiDirect::On;
        break;
    case Backend::Cuda:
        if (!gpu::device_present())
            throw InputError("backend=cuda: no CUDA device is visible to this process "
                             "(or the build has no CUDA); use backend=host");
        // One device per rank (node-local rank modulo the devices); the particle data live
        // there for the whole run, on the default stream.
        engine_->particles.keep_mirror(std::make_unique<exec::ParticleMirror>(exec::cuda_device_memory(), false));
        engine_->bodies_resident.keep_mirror(std::make_unique<exec::ParticleMirror>(exec::cuda_device_memory(), false));
        engine_->target.device = true;
        engine_->target.separate = true;
        engine_->target.direct_mpi = settings.mpi_direct == MpiDirect::On ||
                                     (settings.mpi_direct == MpiDirect::Auto && exec::mpi_reads_device_memory());
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
    engine_->motion.body_langevin = settings;
}

void Simulation::add_force(std::unique_ptr<ForceTerm> term) {
    engine_->forces.add(std::move(term));
}

BoundaryRule* Simulation::add_boundary(std::unique_ptr<BoundaryRule> rule) {
    engine_->boundaries.push_back(std::move(rule));
    return engine_->boundaries.back().get();
}

WallLayerThermostat* Simulation::add_wall_layer(std::unique_ptr<WallLayerThermostat> layer) {
    engine_->motion.wall_layers.push_back(std::move(layer));
    return engine_->motion.wall_layers.back().get();
}

std::vector<const BoundaryRule*> Simulation::boundary_rules() const {
    std::vector<const BoundaryRule*> rules;
    for (const auto& rule : engine_->boundaries) rules.push_back(rule.get());
    return rules;
}

void Simulation::set_thermostat(std::unique_ptr<Thermostat> thermostat) {
    engine_->motion.thermostat = std::move(thermostat);
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
    e.particles.host_reads(kAllFields);
    // A set-up adds its particles one at a time: room doubles here, where the store's own
    // growth by 1/32 (kept for the run's migrations) would copy every array ~30 times into
    // fresh pages. The store is fitted to its size when the set-up ends.
    if (e.store.n_owned() + 1 > e.store.position.capacity())
        e.store.reserve(std::max<std::size_t>(1024, 2 * (e.store.n_owned() + 1)));
    e.store.add_owned(x, v, species, id, diameter);
    e.particles.host_wrote(kAllFields);
}

void Simulation::assign_thermal_velocities(double temperature, std::uint64_t seed) {
    Engine& e = *engine_;
    ParticleStore& s = e.store;
    e.particles.host_reads(kVelocity | kSpecies | kId);
    e.particles.host_wrote(kVelocity);
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
    e.neighbourhood.rebuild();
    if (e.settings.balance == LoadBalance::Cost && e.neighbourhood.rebalance()) e.neighbourhood.rebuild();
    e.count_bodies();
    e.forces.compute(true, e.time);
    // What only the host holds yet (fields the build and the first forces did not need) goes
    // to the back end now, with the set-up, rather than in the first steps.
    e.particles.backend_reads(kAllFields & ~kForce);
    e.bodies_resident.backend_reads(EngineState::kBodyFields & ~(kForce | kTorque));
    e.masses();
    e.inverse_masses();
}

const std::vector<Vec3>& Simulation::list_reference_positions() const {
    return engine_->neighbourhood.reference_positions();
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

const LoadBalanceStats& Simulation::load_balance() const { return engine_->neighbourhood.balance_stats(); }

bool Simulation::halo_overlap() const { return engine_->neighbourhood.overlap_now(); }

double Simulation::interior_fraction() const {
    const Engine& e = *engine_;
    return e.neighbourhood.interior_first() && e.store.n_owned()
               ? double(e.neighbourhood.n_interior()) / double(e.store.n_owned())
               : 0.0;
}

double Simulation::cost_imbalance() const {
    const Engine& e = *engine_;
    const std::vector<std::uint32_t>& cost = e.neighbourhood.particle_costs();
    return decomp::cost_imbalance(e.comm, cost.data(), cost.size());
}

namespace {

/// After a drift: the step's one collective (the rebuild vote, with the thermostat's sum where
/// it acts at the step's start), the thermostat, then the list rebuilt or the ghosts refreshed.
void settle_drift(Integration& motion, Neighbourhood& near, bool defer) {
    Integration::VoteSums sums = motion.vote_sums();
    // Two maxima (decomp::kVoteMaxima: the displacement, the drift), then the kinetic energy.
    double values[3] = {near.local_moved_sq(), sums.step_sq, sums.kinetic};
    near.reduce_vote(values, sums.present ? 3 : 2);
    sums.kinetic = values[2];
    // The rescaling moves each particle by at most |factor - 1| times its drift: the largest
    // displacement is bounded by the sum of the two largest (a NaN carried through).
    const double change = motion.apply_voted_thermostat(sums);
    double moved_sq = values[0];
    if (change > 0) {
        const double bound = std::sqrt(values[0]) + change * std::sqrt(values[1]);
        moved_sq = bound * bound;
    }
    near.follow(near.decide(moved_sq), defer);
}

}  // namespace

void Simulation::step(bool sample) {
    Engine& e = *engine_;
    const exec::Transfers before = exec::transfers();
    const double dt = e.settings.dt;
    // Rebalances by the step's index alone, so a continued run moves the planes where the
    // uninterrupted one did.
    const long long every = e.settings.balance_every;
    e.neighbourhood.begin_step(e.settings.balance == LoadBalance::Cost && every > 0 && (e.step + 1) % every == 0);
    switch (e.settings.integrator) {
    case Integrator::VelocityVerlet:
        e.motion.kick_drift(0.5 * dt, dt, e.time, true);
        settle_drift(e.motion, e.neighbourhood, !sample);
        e.forces.compute(sample, e.time + dt);
        e.motion.kick(0.5 * dt);
        break;
    case Integrator::Omelyan: {
        // lambda minimises the norm of the leading error term (Omelyan, Mryglod & Folk,
        // Comput. Phys. Commun. 146 (2002) 188, eq. 31).
        constexpr double lambda = 0.1931833275037836;
        e.motion.kick_drift(lambda * dt, 0.5 * dt, e.time);
        settle_drift(e.motion, e.neighbourhood, true);
        e.forces.compute(false, e.time + 0.5 * dt);
        e.motion.kick_drift((1 - 2 * lambda) * dt, 0.5 * dt, e.time + 0.5 * dt);
        settle_drift(e.motion, e.neighbourhood, !sample);
        e.forces.compute(sample, e.time + dt);
        e.motion.kick(lambda * dt);
        break;
    }
    }
    e.motion.apply_thermostat();
    e.motion.apply_body_langevin();
    ++e.step;
    e.time += dt;
    e.motion.apply_wall_layers();  // keyed by the step just completed
    if (!e.neighbourhood.built_this_step()) {
        keep_most(sample ? e.ledger.sampled_step : e.ledger.plain_step, work_since(before));
        ++(sample ? e.ledger.sampled_steps : e.ledger.plain_steps);
    }
}

ParticleStore& Simulation::particles() {
    engine_->particles.host_reads(kAllFields);
    engine_->particles.host_wrote(kAllFields);
    return engine_->store;
}
const ParticleStore& Simulation::particles() const {
    engine_->particles.host_reads(kAllFields);
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
    return engine_->forces.cutoff() + engine_->settings.skin;
}
long long Simulation::rebuilds() const { return engine_->neighbourhood.rebuilds(); }
double Simulation::degrees_of_freedom() const { return engine_->dof(); }
const std::vector<double>& Simulation::species_masses() const { return engine_->mass; }
Backend Simulation::backend() const { return engine_->settings.backend; }
bool Simulation::has_thermostat() const { return engine_->motion.thermostat != nullptr; }
bool Simulation::has_bodies() const { return engine_->bodies(); }
ParticleStore& Simulation::bodies() {
    // As particles(): brought up to date, and counted as changed by the caller.
    engine_->bodies_resident.host_reads(EngineState::kBodyFields);
    engine_->bodies_resident.host_wrote(EngineState::kBodyFields);
    return engine_->rigid.store();
}
const ParticleStore& Simulation::bodies() const {
    engine_->bodies_resident.host_reads(EngineState::kBodyFields);
    return engine_->rigid.bodies();
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
bool Simulation::conserves_energy() const {
    const Integration& motion = engine_->motion;
    if (motion.thermostat || motion.body_langevin || !motion.wall_layers.empty() || !engine_->forces.conservative())
        return false;
    for (const auto& rule : engine_->boundaries)
        if (!rule->conservative()) return false;
    return true;
}
const PhaseTimes& Simulation::phase_times() const {
    engine_->times.halo_wait = engine_->neighbourhood.halo().refresh_wait_seconds() - engine_->wait_at_reset;
    return engine_->times;
}

MessageTraffic Simulation::message_traffic() const {
    const Engine& e = *engine_;
    MessageTraffic t = e.neighbourhood.traffic();
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

const StepLedger& Simulation::step_ledger() const { return engine_->ledger; }

void Simulation::reset_phase_times() {
    engine_->ledger = StepLedger{};
    engine_->times = PhaseTimes{};
    engine_->wait_at_reset = engine_->neighbourhood.halo().refresh_wait_seconds();
    engine_->traffic_at_reset = MessageTraffic{};
    engine_->traffic_at_reset = message_traffic();
}

}  // namespace emergent
