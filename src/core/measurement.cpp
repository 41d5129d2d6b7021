// SPDX-License-Identifier: MIT
// What Simulation measures of its state: thermodynamic sums, kinetic parts, coarse-grained field
// sums, the walls' exchange tallies, and the guards that stop a run that has blown up.
#include <cmath>
#include <sstream>

#include "core/engine.hpp"
#include "decomposition/reductions.hpp"
#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "integrate/kick_drift.hpp"
#include "integrate/particle_sums.hpp"
#include "neighbour/list_build_loops.hpp"
#include "observe/field_sampling.hpp"

namespace emergent {

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

void Simulation::check_guards(const GuardLimits& limits) const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    std::string problem = e.boundary_fault;
    const double f2max = limits.max_force * limits.max_force;
    e.particles.backend_reads(kPosition | kVelocity | kForce);
    const integrate::UnfitState unfit{e.data(kPosition, s.position), e.data(kVelocity, s.velocity),
                                      e.data(kForce, s.force), f2max};
    const std::size_t i = problem.empty() ? exec::first_index(e.target, s.n_owned(), unfit) : s.n_owned();
    if (i < s.n_owned()) {
        e.particles.host_reads(kPosition | kVelocity | kForce | kId);  // to name the offender
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

std::vector<double> Simulation::field_sums(const FieldGeometry& grid) const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    const std::size_t n = s.n_owned(), cells = static_cast<std::size_t>(grid.n_cells());
    std::vector<double> sums(cells * observe::kFieldSums);
    if (!e.mirror()) {
        observe::scatter_field_sums(grid, e.box, n, s.position.data(), s.velocity.data(), s.species.data(),
                                    e.mass.data(), sums.data());
        return sums;
    }
    // Where the particles live: sorted by cell (stably, so each cell's members in index order),
    // each cell summed in that order; only the sums come back.
    e.particles.backend_reads(kPosition | kVelocity | kSpecies);
    exec::ParticleMirror& m = *e.mirror();
    auto* key = static_cast<std::uint32_t*>(m.scratch(EngineState::kFieldKeys, n * sizeof(std::uint32_t)));
    auto* member = static_cast<std::uint32_t*>(m.scratch(EngineState::kFieldMembers, n * sizeof(std::uint32_t)));
    auto* start = static_cast<std::uint32_t*>(m.scratch(EngineState::kFieldStart, (cells + 1) * sizeof(std::uint32_t)));
    auto* out = static_cast<double*>(m.scratch(EngineState::kFieldSums, sums.size() * sizeof(double)));
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

ThermoSample Simulation::measure() const {
    const Engine& e = *engine_;
    const ParticleStore& s = e.store;
    const Vec3 len = e.box.length();
    e.particles.backend_reads(kPosition | kVelocity | kImage | kSpecies | kBody);
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
    double v[9] = {e.local_kinetic(), e.forces.sums().potential, e.forces.sums().virial, 0, 0, 0, 0, 0, 0};
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
    exec::count_collective();
    MPI_Allreduce(&e.forces.sums().max_overlap, &t.max_overlap, 1, MPI_DOUBLE, MPI_MAX, e.comm);
    return t;
}

KineticParts Simulation::kinetic_parts() const {
    const Engine& e = *engine_;
    e.particles.backend_reads(kVelocity | kSpecies | kBody);
    const double free = exec::transform_sum<double>(
        e.target, e.store.n_owned(),
        integrate::FreeKineticEnergy{e.data(kVelocity, e.store.velocity), e.data(kSpecies, e.store.species),
                                     e.masses(), e.store.has_rigid_fields() ? e.data(kBody, e.store.body) : nullptr});
    const Vec3 bodies =
        e.bodies() ? e.rigid.kinetic_parts(e.target, e.body_arrays(kVelocity | kSpecies | kOrientation |
                                                                   kAngularMomentum))
                   : Vec3{0, 0, 0};
    double sums[3] = {free, bodies.x, bodies.y};
    exec::count_collective();
    MPI_Allreduce(MPI_IN_PLACE, sums, 3, MPI_DOUBLE, MPI_SUM, e.comm);
    KineticParts k{sums[0], sums[1], sums[2], e.bodies() ? e.n_free : e.n_global,
                   e.bodies() ? e.n_bodies : 0};
    return k;
}

std::vector<double> Simulation::exchange_tallies() const {
    std::vector<double> t;
    for (const auto& rule : engine_->boundaries) {
        const WallExchange e = global_exchange(*rule);
        t.insert(t.end(), {double(e.hits), e.momentum.x, e.momentum.y, e.momentum.z,
                           e.angular_momentum, e.energy});
    }
    for (const auto& layer : engine_->motion.wall_layers) t.push_back(layer->energy());  // global already
    return t;
}

}  // namespace emergent
