// SPDX-License-Identifier: MIT
// Rigid bodies made of constituent spheres: their state, integration and bookkeeping.
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "decomposition/migration.hpp"
#include "emergent/execution.hpp"
#include "emergent/particle_store.hpp"
#include "rigid/body_frame.hpp"
#include "rigid/body_motion.hpp"

namespace emergent::rigid {

/// One kind of body: spheres (species, diameter) at positions in any frame.
struct BodyKind {
    std::vector<Vec3> positions;
    std::vector<int> species;
    std::vector<double> diameters;
};

/// The rigid bodies a rank owns and their constituent spheres.
///
/// A body is owned by the rank whose domain holds its centre of mass; its constituents are
/// owned particles of the same rank (they may stick out of the domain by the body's extent,
/// which the ghost shell covers). Constituents are regenerated from the body state at every
/// neighbour-list build and placed from it at every step, so only bodies migrate. Bodies are
/// stored in a ParticleStore with rigid fields: position = centre of mass, velocity, force,
/// id, species = kind, orientation (principal frame -> space), angular_momentum = NO_SQUISH's
/// conjugate momentum, torque; its `body` field holds the id of the first constituent.
class RigidBodies {
public:
    int add_kind(const BodyKind& kind, const std::vector<double>& species_mass);
    /// Adds a body (on the caller's rank; the caller checks the domain).
    void add(int kind, const Vec3& com, const Quat& orientation, const Vec3& velocity,
             const Vec3& omega_space, std::int64_t id, std::int64_t first_particle_id);

    bool empty_everywhere() const { return kinds_.empty(); }
    double max_extent() const { return max_extent_; }
    std::size_t n_owned() const { return bodies_.n_owned(); }
    const ParticleStore& bodies() const { return bodies_; }
    ParticleStore& store() { return bodies_; }

    /// At a list build: drops constituents from `store`, migrates bodies, appends their
    /// constituents again. Free particles are migrated by the caller before this.
    void drop_constituents(ParticleStore& store) const;
    void migrate(const decomp::RankGrid& grid) { migration_.apply(bodies_, grid); }
    /// What the host's migrations of bodies sent to other ranks.
    const MessageCounts& migration_traffic() const { return migration_.traffic(); }
    void append_constituents(ParticleStore& store) const;
    /// After particles were reordered: where each body's constituents are.
    void index_constituents(const ParticleStore& store);
    /// Empty if every owned body has a known kind and exactly its kind's constituents among
    /// `store`'s owned particles, and every sphere there belongs to an owned body; otherwise
    /// the first mismatch, in words (a restored state that index_constituents cannot use).
    std::string check_constituents(const ParticleStore& store) const;

    /// Where the loops over bodies read and write: the bodies' arrays, their frames and the
    /// constituent index, in host memory (host_arrays()) or in a back end's.
    struct Arrays {
        BodyState state;
        FrameTable frames;
        ConstituentIndex constituents;
        const std::int64_t* id = nullptr;
        const Int3* image = nullptr;
    };
    /// The store's own arrays (the const passes only read through them).
    Arrays host_arrays() const;
    /// Places every owned body's constituents at the slots `at` says (positions and
    /// velocities, rigid::place_constituents) on `target`: one loop for the host's append and
    /// the back end's list build, so both give the same bits.
    void place_at(const exec::Target& target, const Arrays& a, const ConstituentIndex& at, Vec3* x, Vec3* v) const;
    /// The flat tables behind FrameTable and ConstituentIndex, for copying to a back end.
    const std::vector<double>& frame_masses() const { return frame_mass_; }
    const std::vector<Vec3>& frame_inertia() const { return frame_inertia_; }
    const std::vector<std::uint32_t>& frame_first() const { return frame_first_; }
    const std::vector<Vec3>& frame_positions() const { return frame_positions_; }
    /// Species and diameters of the constituents, aligned with frame_positions().
    const std::vector<int>& frame_species() const { return frame_species_; }
    const std::vector<double>& frame_diameters() const { return frame_diameters_; }
    const std::vector<std::uint32_t>& constituent_first() const { return first_; }
    const std::vector<std::uint32_t>& constituent_index() const { return index_; }

    /// Splitting stages for bodies, durations given (velocity Verlet: kick dt/2 and drift dt):
    /// momentum and angular momentum kicked, then translation and free rotation (NO_SQUISH),
    /// then constituents placed. Loops run on `target` over `a` and the constituents' x, v, f
    /// (the same memory).
    void kick_drift(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double kick,
                    double drift) const;
    void sum_forces(const exec::Target& target, const Arrays& a, const Vec3* x, const Vec3* f) const;
    /// `place` false leaves the constituents' velocities to a pass that follows (Langevin).
    void kick(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double kick,
              bool place = true) const;
    /// One step of Langevin dynamics (BodyLangevin) for every owned body.
    void langevin(const exec::Target& target, const Arrays& a, Vec3* x, Vec3* v, double decay_t,
                  double decay_r, double temperature, std::uint64_t seed, std::uint64_t step) const;

    /// Kinetic energy (translation + rotation), momentum, angular momentum about the origin
    /// (unwrapped centres) of the owned bodies; and their degrees of freedom (6 each).
    double kinetic(const exec::Target& target, const Arrays& a) const;
    /// The same split: translational (x) and rotational (y).
    Vec3 kinetic_parts(const exec::Target& target, const Arrays& a) const;
    Vec3 momentum(const exec::Target& target, const Arrays& a) const;
    Vec3 angular_momentum(const exec::Target& target, const Arrays& a, const Vec3& box_length) const;

private:
    std::vector<BodyKind> kinds_;
    std::vector<BodyFrame> frames_;
    std::vector<std::vector<double>> kind_masses_;
    double max_extent_ = 0;
    ParticleStore bodies_;
    decomp::Migration migration_;
    std::vector<std::uint32_t> first_, index_;  // constituent indices of body b: index_[first_[b]..]
    // frames_ as flat arrays (FrameTable)
    std::vector<double> frame_mass_;
    std::vector<Vec3> frame_inertia_, frame_positions_;
    std::vector<std::uint32_t> frame_first_{0};
    std::vector<int> frame_species_;
    std::vector<double> frame_diameters_;
};

}  // namespace emergent::rigid
