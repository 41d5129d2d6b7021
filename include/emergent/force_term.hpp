// SPDX-License-Identifier: MIT
// A contribution to the forces: pair potentials, walls, external fields.
#pragma once

#include <memory>
#include <string>

#include "emergent/particle_store.hpp"

namespace emergent {

class NeighbourList;

/// Potential energy and virial accumulated by force terms on sampling steps.
struct ForceSums {
    double potential = 0;  ///< sum of potential energy over owned particles' share
    double virial = 0;     ///< W = sum over pairs of r_ij . f_ij (trace of the virial tensor)
};

/// One term of the force field. The engine sums all terms every step; energy and virial are
/// asked for only on sampling steps so the hot path never computes them.
class ForceTerm {
public:
    virtual ~ForceTerm() = default;
    virtual std::string name() const = 0;
    /// Largest pair distance the term needs listed (0 for terms without pairs).
    virtual double cutoff() const = 0;
    /// Fields ghost particles must carry for this term.
    virtual unsigned ghost_fields() const { return kPosition; }
    /// Adds the term's forces to store.force; when `sample`, also its energy and virial.
    virtual void add_forces(ParticleStore& store, const NeighbourList& list, bool sample,
                            ForceSums& sums) const = 0;
};

/// Lennard-Jones 4 eps [(sigma/r)^12 - (sigma/r)^6], truncated at `cutoff` and shifted to zero
/// there; cutoff = 2^(1/6) sigma gives the purely repulsive WCA potential.
std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff);

}  // namespace emergent
