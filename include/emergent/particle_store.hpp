// SPDX-License-Identifier: MIT
// Structure-of-arrays storage of the particles a rank holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "emergent/quaternion.hpp"
#include "emergent/vec3.hpp"

namespace emergent {

/// Bit flags naming the per-particle fields, so communication can be asked for a subset
/// ("ghosts need position and species") without knowing what the fields mean.
enum FieldMask : unsigned {
    kPosition = 1u << 0,
    kVelocity = 1u << 1,
    kForce = 1u << 2,
    kSpecies = 1u << 3,
    kId = 1u << 4,
    kImage = 1u << 5,
    kDiameter = 1u << 6,
    kBody = 1u << 7,         ///< rigid fields, present only after enable_rigid_fields()
    kOrientation = 1u << 8,
    kAngularMomentum = 1u << 9,
    kTorque = 1u << 10,
    kAllFields = ~0u,
};

/// Untyped view of one per-particle array: what decomposition packs and unpacks.
struct FieldSpan {
    FieldMask field;
    std::size_t element_bytes;
    void* data;
};

/// The particles of one rank, stored field by field.
///
/// Nomenclature (as in the decomposition layer):
///  - *owned* particles, indices [0, n_owned), are integrated by this rank;
///  - *ghost* particles, indices [n_owned, size()), are copies of particles owned by this or
///    another rank (periodic images included), present only so owned particles see all their
///    neighbours. Ghosts carry the fields the force terms ask for; their other fields are stale.
class ParticleStore {
public:
    std::vector<Vec3> position;        ///< unwrapped within the home box; image counts the wraps
    std::vector<Vec3> velocity;
    std::vector<Vec3> force;
    std::vector<int> species;          ///< index into the species tables
    std::vector<std::int64_t> id;      ///< global, unique, stable over the run
    std::vector<Int3> image;           ///< periodic box crossings since the start
    std::vector<Real> diameter;        ///< contact diameter (granular models; 1 otherwise)
    // Rigid fields (empty unless enable_rigid_fields()): for a constituent sphere, the id of
    // its body (-1 for free particles); for a body store (position = centre of mass), the
    // orientation, the conjugate momentum of NO_SQUISH and the torque.
    std::vector<std::int64_t> body;
    std::vector<Quat> orientation;
    std::vector<Quat> angular_momentum;
    std::vector<Vec3> torque;

    /// Gives every particle the rigid fields from now on (costs memory only where used).
    void enable_rigid_fields();
    bool has_rigid_fields() const { return rigid_; }

    std::size_t n_owned() const { return n_owned_; }
    std::size_t n_ghost() const { return position.size() - n_owned_; }
    std::size_t size() const { return position.size(); }

    /// Appends one owned particle (drops any ghosts first).
    void add_owned(const Vec3& x, const Vec3& v, int species_index, std::int64_t global_id,
                   Real particle_diameter = 1.0);

    /// Keeps the first n owned particles and drops all ghosts.
    void resize_owned(std::size_t n);

    /// Sets the number of ghosts after the owned particles; ghost contents are left to the caller.
    void resize_ghosts(std::size_t n);

    /// Reorders the owned particles: new index k holds the particle that was at order[k].
    void permute_owned(const std::vector<std::uint32_t>& order);

    /// Calls visit(FieldSpan) for every per-particle array.
    template <class Visitor>
    void for_each_field(Visitor&& visit) {
        visit(FieldSpan{kPosition, sizeof(Vec3), position.data()});
        visit(FieldSpan{kVelocity, sizeof(Vec3), velocity.data()});
        visit(FieldSpan{kForce, sizeof(Vec3), force.data()});
        visit(FieldSpan{kSpecies, sizeof(int), species.data()});
        visit(FieldSpan{kId, sizeof(std::int64_t), id.data()});
        visit(FieldSpan{kImage, sizeof(Int3), image.data()});
        visit(FieldSpan{kDiameter, sizeof(Real), diameter.data()});
        if (!rigid_) return;
        visit(FieldSpan{kBody, sizeof(std::int64_t), body.data()});
        visit(FieldSpan{kOrientation, sizeof(Quat), orientation.data()});
        visit(FieldSpan{kAngularMomentum, sizeof(Quat), angular_momentum.data()});
        visit(FieldSpan{kTorque, sizeof(Vec3), torque.data()});
    }

private:
    void resize_all(std::size_t n);

    std::size_t n_owned_ = 0;
    bool rigid_ = false;
    std::vector<unsigned char> scratch_;
};

}  // namespace emergent
