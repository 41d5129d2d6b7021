// SPDX-License-Identifier: MIT
// Granular contacts between spheres.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "emergent/error.hpp"
#include "emergent/execution.hpp"
#include "force/dispatch.hpp"
#include "force/per_particle_term.hpp"
#include "force/granular_contact.hpp"
#include "force/contact_law.hpp"
#include "force/uniform_field.hpp"
#include "neighbour/neighbour_list.hpp"

namespace emergent {

namespace {

/// Contacts over the half list (host code) for the features chosen by dispatch_bools.
struct ContactLoop {
    ParticleStore& store;
    const NeighbourList& list;
    const GranularSettings& settings;
    ForceSums& sums;
    const ForceContext& rows;
    template <bool Sample, bool Damping, bool Friction, bool Table>
    void operator()() const {
        using Law = force::ContactLaw<force::ContactFeatures<Sample, Damping, Friction, Table>,
                                      force::HostContactPairs>;
        const Law law{{settings.pairs.data()}, settings.n_species, 0.5 * settings.range_factor};
        const force::PairArrays a{store.position.data(), store.velocity.data(), store.diameter.data(),
                                  store.species.data(),  store.force.data(),    list.offsets(),
                                  list.neighbours()};
        const force::PairSums s = force::pair_forces_half_list<Sample>(law, a, list.n_owned(), rows.first, rows.last);
        sums.potential += s.energy;
        sums.virial += s.virial;
        if constexpr (Sample) sums.max_overlap = std::max(sums.max_overlap, s.overlap);
    }
};

/// Contacts over the full list (the back end's form) for the features chosen by dispatch_bools.
struct FullListContacts {
    const BackendParticles& p;
    const force::ContactTable& table;
    const GranularSettings& settings;
    ForceSums& sums;
    template <bool Sample, bool Damping, bool Friction, bool Table>
    void operator()() const {
        using Law = force::ContactLaw<force::ContactFeatures<Sample, Damping, Friction, Table>, force::ContactTable>;
        const force::PairArrays a{p.position, p.velocity, p.diameter, p.species, p.force, p.list_offset, p.list_index};
        const force::PairForcesFullList<Law, Sample> contacts{
            Law{table, settings.n_species, 0.5 * settings.range_factor}, a, p.energy, p.virial, p.overlap};
        exec::for_each(p.target, p.n_owned, contacts);
        if constexpr (Sample) force::add_sampled(p, p.n_owned, true, sums);
    }
};

/// A plane wall's contacts for the features chosen by dispatch_bools (both forms: the host's
/// store seen as BackendParticles).
struct WallContacts {
    const BackendParticles& p;
    int axis, side;
    double position, range;
    const GranularPair& pair;
    const Vec3& velocity;
    ForceSums& sums;
    template <bool Sample, bool Damping, bool Friction>
    void operator()() const {
        exec::for_each(p.target, p.n_owned,
                       force::PlaneWallForce<Sample, Damping, Friction>{
                           p.position, p.velocity, p.diameter, p.force, axis, Real(side), position,
                           range, pair, velocity, p.energy, p.overlap});
        if constexpr (Sample) force::add_sampled(p, p.n_owned, false, sums);
    }
};

class GranularContacts final : public ForceTerm {
public:
    explicit GranularContacts(const GranularSettings& g) : g_(g) {
        for (const auto& p : g.pairs) {
            damping_ = damping_ || p.gamma_n != 0;
            friction_ = friction_ || (p.gamma_s != 0 && p.mu != 0);
        }
        if (on_backend())
            for (std::size_t k = 0; k < g.pairs.size(); ++k) table_.pair[k] = g.pairs[k];
    }
    std::string name() const override { return "granular-contacts"; }
    bool conservative() const override { return !damping_ && !friction_; }
    double cutoff() const override { return g_.range_factor * g_.max_diameter; }
    unsigned ghost_fields() const override {
        const bool velocities = damping_ || friction_ || g_.generic;
        return kPosition | kSpecies | kDiameter | (velocities ? unsigned(kVelocity) : 0u);
    }
    void add_forces(ParticleStore& store, const NeighbourList& list, const ForceContext& rows,
                    bool sample, ForceSums& sums) const override {
        const bool all = g_.generic;
        force::dispatch_bools(ContactLoop{store, list, g_, sums, rows}, sample, damping_ || all,
                              friction_ || all, g_.n_species > 1 || all);
    }
    bool honours_range() const override { return true; }
    /// The laws travel by value with the loop: up to kContactTableSpecies species.
    bool on_backend() const override { return g_.n_species <= force::kContactTableSpecies; }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext&, bool sample,
                               ForceSums& sums) const override {
        const bool all = g_.generic;
        force::dispatch_bools(FullListContacts{p, table_, g_, sums}, sample, damping_ || all,
                              friction_ || all, g_.n_species > 1 || all);
    }

private:
    GranularSettings g_;
    bool damping_ = false, friction_ = false;
    force::ContactTable table_{};
};

class UniformField final : public ForceTerm {
public:
    explicit UniformField(const Vec3& g) : g_(g) {}
    std::string name() const override { return "uniform-field"; }
    double cutoff() const override { return 0; }
    bool on_backend() const override { return true; }
    void add_forces(ParticleStore& s, const NeighbourList& list, const ForceContext& c,
                    bool sample, ForceSums& sums) const override {
        add(exec::Target{}, s.position.data(), s.force.data(), s.species.data(), c.mass->data(),
            list.n_owned(), sample, sums);
    }
    void add_forces_on_backend(const BackendParticles& p, const ForceContext&, bool sample,
                               ForceSums& sums) const override {
        add(p.target, p.position, p.force, p.species, p.mass, p.n_owned, sample, sums);
    }

private:
    void add(const exec::Target& target, const Vec3* x, Vec3* f, const int* species,
             const double* mass, std::size_t n, bool sample, ForceSums& sums) const {
        // The sampling in its own pass: the force pass is then a plain streaming add (it runs
        // every step for every particle).
        exec::for_each(target, n, force::AddUniformField{f, species, mass, g_});
        if (!sample) return;
        sums.potential +=
            exec::transform_sum<double>(target, n, force::UniformFieldEnergy{x, species, mass, g_});
    }

    Vec3 g_;
};

class PlaneWall final : public force::PerParticleWall {
public:
    PlaneWall(int axis, double position, int side, const GranularPair& p, double range,
              const Vec3& velocity)
        : axis_(axis), position_(position), side_(side), p_(p), range_(range), velocity_(velocity) {}
    std::string name() const override { return "plane-wall"; }
    bool conservative() const override {
        return p_.gamma_n == 0 && (p_.gamma_s == 0 || p_.mu == 0) && dot(velocity_, velocity_) == 0;
    }

private:
    void add(const BackendParticles& p, double, bool sample, ForceSums& sums) const override {
        const bool damping = p_.gamma_n != 0, friction = p_.gamma_s != 0 && p_.mu != 0;
        force::dispatch_bools(WallContacts{p, axis_, side_, position_, range_, p_, velocity_, sums},
                              sample, damping, friction);
    }

    int axis_;
    double position_;
    int side_;
    GranularPair p_;
    double range_;
    Vec3 velocity_;
};

}  // namespace

void force::check_granular_pair(const GranularPair& p, const std::string& what) {
    if (!(p.k_n > 0) || p.gamma_n < 0 || p.gamma_s < 0 || p.mu < 0) {
        std::ostringstream msg;
        msg << what << ": k_n=" << p.k_n << " must be > 0 and gamma_n=" << p.gamma_n
            << ", gamma_s=" << p.gamma_s << ", mu=" << p.mu << " >= 0";
        throw InputError(msg.str());
    }
}

std::unique_ptr<ForceTerm> make_granular_contacts(const GranularSettings& g) {
    if (g.n_species < 1 || g.pairs.size() != static_cast<std::size_t>(g.n_species * g.n_species))
        throw InputError("granular contacts: need n_species^2 pair entries");
    for (const auto& p : g.pairs) force::check_granular_pair(p, "granular contacts");
    if (!(g.range_factor > 0) || !(g.max_diameter > 0))
        throw InputError("granular contacts: range_factor and max_diameter must be > 0");
    return std::make_unique<GranularContacts>(g);
}

std::unique_ptr<ForceTerm> make_uniform_field(const Vec3& acceleration) {
    return std::make_unique<UniformField>(acceleration);
}

std::unique_ptr<ForceTerm> make_plane_wall(int axis, double position, int side,
                                           const GranularPair& contact, double range_factor,
                                           const Vec3& wall_velocity) {
    if (axis < 0 || axis > 2 || (side != 1 && side != -1))
        throw InputError("plane wall: axis must be 0..2 and side +1 or -1");
    force::check_granular_pair(contact, "plane wall");
    return std::make_unique<PlaneWall>(axis, position, side, contact, range_factor, wall_velocity);
}

}  // namespace emergent
