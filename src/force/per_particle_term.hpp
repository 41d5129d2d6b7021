// SPDX-License-Identifier: MIT
// What force terms acting on each particle alone (walls, bases, fields) share: the host's
// store seen as the back end's particles, so one loop serves both forms, and the sums a
// sampling pass leaves per particle.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/execution.hpp"
#include "emergent/force_term.hpp"
#include "force/granular_contact.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent::force {

/// The store's owned particles as BackendParticles, with per-particle energy and overlap
/// scratch on sampling steps: a term's host form runs its back-end loop on it.
struct HostParticles {
    std::vector<Real> energy, overlap;
    BackendParticles p;
    HostParticles(ParticleStore& s, const std::vector<double>& mass, std::size_t n_owned, bool sample)
        : p(host_view(s, mass)) {
        p.n_owned = n_owned;
        if (!sample) return;
        energy.resize(n_owned);
        overlap.resize(n_owned);
        p.energy = energy.data();
        p.overlap = overlap.data();
    }
};

/// A wall's contact law on each particle alone: f[i] += law(x, v, d, tally); with Sample,
/// energy[i] and overlap[i] (in diameters) get what the law tallied (its contacts' energy and
/// the largest overlap). Law: EMERGENT_HD Vec3 operator()(x, v, d, ContactTally*), the tally
/// null when not sampling.
template <bool Sample, class Law>
struct TalliedWallForce {
    const Vec3* x;
    const Vec3* v;
    const Real* diameter;
    Vec3* f;
    Law law;
    Real* energy = nullptr;
    Real* overlap = nullptr;

    EMERGENT_HD void operator()(std::size_t i) const {
        ContactTally tally;
        f[i] += law(x[i], v[i], diameter[i], Sample ? &tally : nullptr);
        if constexpr (Sample) {
            energy[i] = tally.energy;
            overlap[i] = tally.max_overlap;
        }
    }
};

/// A granular wall or base acting on each particle alone: one loop, written for the back end's
/// particles, serves both forms (the host form runs it on the store through HostParticles).
/// A term implements add() for the particles given; it reads positions, velocities and
/// diameters.
class PerParticleWall : public ForceTerm {
public:
    double cutoff() const override { return 0; }
    unsigned particle_fields() const override { return kPosition | kVelocity | kDiameter; }
    bool on_backend() const override { return true; }
    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& c, bool sample,
                    ForceSums& sums) const final {
        add(HostParticles(s, *c.mass, list.n_owned(), sample).p, c.time, sample, sums);
    }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext& c, bool sample,
                               ForceSums& sums) const final {
        add(p, c.time, sample, sums);
    }

protected:
    /// The term's forces on p's owned particles at time `time`; when `sample`, its energy and
    /// largest overlap too (add_sampled).
    virtual void add(const BackendParticles& p, double time, bool sample, ForceSums& sums) const = 0;
    /// Runs the per-particle functor over p's owned particles, then adds what a sampling pass
    /// left (its functor wrote p.energy and p.overlap).
    template <bool Sample, class Functor>
    static void launch(const BackendParticles& p, const Functor& f, ForceSums& sums);
    /// launch() of a contact law through TalliedWallForce.
    template <bool Sample, class Law>
    static void launch_law(const BackendParticles& p, const Law& law, ForceSums& sums) {
        launch<Sample>(p, TalliedWallForce<Sample, Law>{p.position, p.velocity, p.diameter, p.force, law, p.energy, p.overlap},
                       sums);
    }
};

/// Adds what a sampling pass left in p.energy, p.virial (if `virial`) and p.overlap.
inline void add_sampled(const BackendParticles& p, std::size_t n, bool virial, ForceSums& sums) {
    sums.potential += exec::transform_sum<double>(p.target, n, exec::ElementOf<Real>{p.energy});
    if (virial) sums.virial += exec::transform_sum<double>(p.target, n, exec::ElementOf<Real>{p.virial});
    sums.max_overlap = std::max(
        sums.max_overlap, exec::transform_max(p.target, n, 0.0, exec::ElementOf<Real>{p.overlap}));
}

template <bool Sample, class Functor>
void PerParticleWall::launch(const BackendParticles& p, const Functor& f, ForceSums& sums) {
    exec::for_each(p.target, p.n_owned, f);
    if constexpr (Sample) add_sampled(p, p.n_owned, false, sums);
}

}  // namespace emergent::force
