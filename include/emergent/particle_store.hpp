// SPDX-License-Identifier: MIT
// Structure-of-arrays storage of the particles a rank holds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <tuple>
#include <utility>
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
    std::vector<Real> diameter;        ///< contact diameter: present only after enable_diameters()
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
    /// Gives every particle a diameter (1 until set) from now on: models with contacts need
    /// them, a fluid does not pay for them. Adding a particle whose diameter is not 1 enables
    /// them too.
    void enable_diameters();
    bool has_diameters() const { return diameters_; }

    std::size_t n_owned() const { return n_owned_; }
    std::size_t n_ghost() const { return size() - n_owned_; }
    std::size_t size() const { return deferred_ ? deferred_size_ : position.size(); }

    /// While the arrays' contents live elsewhere (a back end's memory: ParticleMirror),
    /// resize_owned() and resize_ghosts() change the counts only, and end_deferred_resize()
    /// sizes the arrays once, to the last count: growing an array constructs its new elements,
    /// and a list build that drops and re-adds most particles (rigid bodies' spheres, ghosts)
    /// would otherwise fill them all on the host at every build. The arrays must not be read
    /// in between.
    void begin_deferred_resize();
    void end_deferred_resize();
    bool resize_deferred() const { return deferred_; }

    /// Appends one owned particle (drops any ghosts first).
    void add_owned(const Vec3& x, const Vec3& v, int species_index, std::int64_t global_id,
                   Real particle_diameter = 1.0);

    /// Keeps the first n owned particles and drops all ghosts.
    void resize_owned(std::size_t n);

    /// Sets the number of ghosts after the owned particles; ghost contents are left to the caller.
    void resize_ghosts(std::size_t n);

    /// Reorders the owned particles: new index k holds the particle that was at order[k]
    /// (distinct indices). `order` may select fewer than all (a resize_owned() then drops the
    /// rest). Only `fields` are moved (the others are left as they were: e.g. forces that are
    /// recomputed next).
    void permute_owned(const std::vector<std::uint32_t>& order, unsigned fields = kAllFields);

    /// Room for n particles in every array, without changing the size.
    void reserve(std::size_t n);

    /// Releases capacity beyond the present size (after the particles are placed: growth by
    /// appending one at a time may leave arrays nearly twice as large as needed).
    void fit_capacity();

    /// Calls visit(FieldSpan) for every per-particle array.
    template <class Visitor>
    void for_each_field(Visitor&& visit) {
        for_each_array([&](const auto& entry, auto& array) {
            visit(FieldSpan{entry.mask, sizeof(entry.fill), static_cast<void*>(array.data())});
        });
    }

    /// Copies the owned part of the `fields` of `from` (its rigid fields too, if it has them);
    /// the other arrays are left empty, so a partial copy costs only what it holds. Such a
    /// store is for keeping state (a last good state): resize_owned() makes it whole again.
    void copy_owned(const ParticleStore& from, unsigned fields);

private:
    /// One per-particle array: its flag, the member, and the value new elements start with.
    template <class T>
    struct Field {
        FieldMask mask;
        std::vector<T> ParticleStore::*member;
        T fill;
    };

    /// The per-particle arrays, listed once: resizing, permuting, packing and copying all walk
    /// this table. Rigid fields come last and exist only after enable_rigid_fields(); diameters
    /// only after enable_diameters().
    static auto field_table() {
        return std::make_tuple(
            Field<Vec3>{kPosition, &ParticleStore::position, {0, 0, 0}},
            Field<Vec3>{kVelocity, &ParticleStore::velocity, {0, 0, 0}},
            Field<Vec3>{kForce, &ParticleStore::force, {0, 0, 0}},
            Field<int>{kSpecies, &ParticleStore::species, 0},
            Field<std::int64_t>{kId, &ParticleStore::id, 0},
            Field<Int3>{kImage, &ParticleStore::image, {0, 0, 0}},
            Field<Real>{kDiameter, &ParticleStore::diameter, 1},
            Field<std::int64_t>{kBody, &ParticleStore::body, -1},
            Field<Quat>{kOrientation, &ParticleStore::orientation, Quat{}},
            Field<Quat>{kAngularMomentum, &ParticleStore::angular_momentum, Quat{0, 0, 0, 0}},
            Field<Vec3>{kTorque, &ParticleStore::torque, {0, 0, 0}});
    }

    /// Calls visit(field entry, this store's array) for every array this store has.
    template <class Visitor>
    void for_each_array(Visitor&& visit) {
        std::apply([&](const auto&... entry) {
            ((present(entry.mask) ? visit(entry, this->*entry.member) : void()), ...);
        }, field_table());
    }

    bool present(FieldMask mask) const {
        return mask == kDiameter ? diameters_ : (mask < kBody || rigid_);
    }

    void resize_all(std::size_t n);

    std::size_t n_owned_ = 0;
    bool deferred_ = false;
    std::size_t deferred_size_ = 0;
    bool rigid_ = false;
    bool diameters_ = false;
};

}  // namespace emergent
