// SPDX-License-Identifier: MIT
// A contribution to the forces: pair potentials, walls, external fields.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "emergent/backend_particles.hpp"
#include "emergent/box.hpp"
#include "emergent/particle_store.hpp"

namespace emergent {

class NeighbourList;

/// What a force term may need besides the particles: species masses, the box, the time.
struct ForceContext {
    const std::vector<double>* mass = nullptr;  ///< per species
    Box box;
    double time = 0;
    /// The owned particles whose rows of the half list this call covers, [first, last) (clipped
    /// to the owned particles): the engine splits a step's pair forces into the rows that
    /// need no ghost and the rest, computing the first while ghost positions are in flight.
    /// Only terms whose honours_range() is true are called with less than all rows.
    std::size_t first = 0, last = static_cast<std::size_t>(-1);
    /// On the back end: the owned particles' forces hold nothing yet, and the term's forces
    /// replace them instead of adding (the engine skips clearing them; only for its first
    /// term, and only where that term says ForceTerm::stores_on_backend()).
    bool replace_forces = false;
};

/// Potential energy and virial accumulated by force terms on sampling steps.
struct ForceSums {
    double potential = 0;  ///< sum of potential energy over owned particles' share
    double virial = 0;     ///< W = sum over pairs of r_ij . f_ij (trace of the virial tensor)
    /// Largest overlap of any granular contact, in units of its sphere diameter (a pair's mean
    /// diameter); stays -1 when no term has contacts.
    double max_overlap = -1;
};

/// One term of the force field. The engine sums all terms every step; energy and virial are
/// asked for only on sampling steps so the hot path never computes them.
class ForceTerm {
public:
    virtual ~ForceTerm() = default;
    virtual std::string name() const = 0;
    /// Largest pair distance the term needs listed (0 for terms without pairs).
    virtual double cutoff() const = 0;
    /// The range by species pair, where it differs from cutoff(): n x n entries (row i, column
    /// j: the distance beyond which the force between species i and j is zero; 0 where they
    /// never interact) for species 0 .. n - 1; pairs with a species from n on meet at
    /// cutoff(). Empty (the default): cutoff() for every pair. The neighbour list keeps a pair
    /// only within the largest range any term gives it (plus the skin): in a solvent of short
    /// range around long-ranged sites, most pairs.
    virtual std::vector<double> pair_ranges() const { return {}; }
    /// False when the term dissipates or injects energy (damping, friction, moving walls): the
    /// total energy is then not conserved and the drift guard does not apply.
    virtual bool conservative() const { return true; }
    /// Fields ghost particles must carry for this term.
    virtual unsigned ghost_fields() const { return kPosition; }
    /// Fields the term reads of the particles it acts on (by default those of the ghosts); the
    /// engine keeps optional ones (diameters) only when some term reads them.
    virtual unsigned particle_fields() const { return ghost_fields(); }
    /// Adds the term's forces to store.force; when `sample`, also its energy and virial.
    virtual void add_forces(ParticleStore& store, const NeighbourList& list,
                            const ForceContext& context, bool sample, ForceSums& sums) const = 0;
    /// True when add_forces() visits only the rows [context.first, context.last) of the half
    /// list, in increasing order, adding nothing else (so two calls over adjacent row ranges
    /// add, bit for bit, what one call over both does). Pair terms that say so let the engine
    /// overlap the ghost refresh with their forces.
    virtual bool honours_range() const { return false; }
    /// True when the term also has the back end's form below: then the engine can keep the
    /// particles on the back end through the force computation.
    virtual bool on_backend() const { return false; }
    /// The back end's form: adds the forces of the owned particles to particles.force, as
    /// functors through the execution layer over the full list; when `sample`, also energy and
    /// virial, with the same meaning as add_forces().
    virtual void add_forces_on_backend(const BackendParticles& particles, const ForceContext& context,
                                       bool sample, ForceSums& sums) const;
    /// True when add_forces_on_backend() writes every owned particle's force and honours
    /// context.replace_forces: as the first term, it spares the engine a pass clearing them.
    virtual bool stores_on_backend() const { return false; }
};

/// Lennard-Jones 4 eps [(sigma/r)^12 - (sigma/r)^6], truncated at `cutoff` and shifted to zero
/// there; cutoff = 2^(1/6) sigma gives the purely repulsive WCA potential. `generic` runs it
/// through the pair loop with every feature compiled in and inactive (species table, pairwise
/// damping with gamma 0, energy and virial every step): the same forces, for measuring what
/// specialisation saves.
std::unique_ptr<ForceTerm> make_lennard_jones(double epsilon, double sigma, double cutoff,
                                              bool generic = false);

/// The purely repulsive WCA fluid of the hydrodynamic scenes (epsilon = sigma = 1).
inline std::unique_ptr<ForceTerm> make_wca() {
    return make_lennard_jones(1.0, 1.0, 1.122462048309373);  // 2^(1/6)
}

/// Contact law of one pair of species (paper eqs. 2, 7, 8): overlap repulsion
/// u = (k_n / 2)(r_c - r)^2, normal damping f_d = -gamma_n (n.v) n, and sliding friction
/// f_s = -min(gamma_s |v_t|, mu |f_l + f_d|) v_t / |v_t|.
struct GranularPair {
    double k_n = 1000, gamma_n = 0, gamma_s = 0, mu = 0;
};

/// Granular contacts between spheres of per-particle diameter: r_c = range_factor (d_i + d_j)/2
/// (range_factor 2^(1/6) gives the paper's convention). `pairs` holds n_species^2 entries
/// (row-major, symmetric). `max_diameter` bounds every diameter (it sets the list cutoff).
/// `generic` forces the kernel with every feature compiled in (for benchmarks).
struct GranularSettings {
    int n_species = 1;
    std::vector<GranularPair> pairs{GranularPair{}};
    double range_factor = 1.0;
    double max_diameter = 1.0;
    bool generic = false;
};
std::unique_ptr<ForceTerm> make_granular_contacts(const GranularSettings& settings);

/// Soft spheres with attraction sites (the capsid model, paper eq. 6). Species below
/// `first_site` are soft spheres: WCA repulsion (epsilon = sigma = 1, cut and shifted at
/// 2^(1/6)) between every two of them. Species first_site + k are attraction sites of type k,
/// points without volume that meet only their partner type, partner[k] (mutual), with
/// u_a = e (1/r_a^2 + r^2/r_h^4 - 2/r_h^2) for r < r_h and e (1/r_a^2 - 1/r^2) for
/// r_h <= r < r_a (e = `epsilon`, r_a = `range`, r_h = `harmonic_range`; 0 beyond r_a, where the
/// force drops by 2e/r_a^3, as published). Constituents of one rigid body never interact.
struct SiteAttraction {
    int first_site = 1;
    std::vector<int> partner;
    double epsilon = 0.09, range = 3, harmonic_range = 0.3;
};
std::unique_ptr<ForceTerm> make_soft_spheres_and_sites(const SiteAttraction& sites);

/// A uniform acceleration field (gravity): f = m g on every particle; u = -m g.x.
std::unique_ptr<ForceTerm> make_uniform_field(const Vec3& acceleration);

/// A flat wall normal to `axis` at `position`; particles live on the side `side` (+1: above,
/// -1: below) and touch it with the contact law `contact` at r_c = range_factor d_i / 2.
/// The wall moves with velocity `wall_velocity` (it enters the damping and friction only).
std::unique_ptr<ForceTerm> make_plane_wall(int axis, double position, int side,
                                           const GranularPair& contact, double range_factor = 1.0,
                                           const Vec3& wall_velocity = {0, 0, 0});

/// A vibrating base of thin rods laid along a periodic profile (paper: the sawtooth base of the
/// vibrated layer). The profile is a polyline z(u) over one period, `vertices` (u, z) from u = 0
/// to u = period with the same z at both ends (at most 5 vertices); rods of diameter
/// `rod_diameter` lie along it `rod_spacing` apart (each edge divided evenly). `rings` false:
/// the rods are lines along y at u = x (a box's straight teeth); true: rings about the z axis of
/// radius u (a round container's concentric teeth). Rods exist for u_lo <= u <= u_hi (the
/// container's floor; unbounded for a floor periodic in x). The whole base moves vertically,
/// z_b(t) = amplitude sin(2 pi frequency t). A sphere meets a rod with overlap repulsion and
/// normal damping of `contact` (no sliding friction) acting in the plane normal to the rod,
/// at r_c = range_factor (d + rod_diameter) / 2. `backing`: a smooth surface along the profile
/// behind the rods, met at r_c = range_factor d / 2 (so only by a sphere pressed between the
/// rods deeper than they let it go), that also pushes back out a sphere below the profile.
struct RodBase {
    std::vector<std::pair<double, double>> vertices{{0.0, 0.0}, {1.0, 0.0}};
    double period = 1;
    double rod_spacing = 0.5, rod_diameter = 0.2;
    bool rings = false;
    double u_lo = -1e300, u_hi = 1e300;
    double amplitude = 0, frequency = 0;
    bool backing = false;
};
std::unique_ptr<ForceTerm> make_rod_base(const RodBase& base, const GranularPair& contact,
                                         double range_factor = 1.0);
/// The rods' centres (u, z) at rest (z_b = 0) with lo <= u <= hi, for pictures and tests.
std::vector<std::pair<double, double>> rod_base_rods(const RodBase& base, double lo, double hi);

/// A smooth cylindrical wall about the z axis (through x = y = 0) of radius `radius`, holding
/// spheres inside with the contact law `contact` at r_c = range_factor d / 2 from the surface;
/// no sliding friction (the paper's smooth container walls).
std::unique_ptr<ForceTerm> make_cylinder_wall(double radius, const GranularPair& contact,
                                              double range_factor = 1.0);

/// The drum's curved wall: a cylinder about the z axis (through x = y = 0) of radius `radius`,
/// spanning z_lo..z_hi, turning at `omega` about +z, made rough by spheres of diameter
/// `sphere_diameter` embedded with their centres on it on a staggered grid of spacing `spacing`
/// (nearest wall spheres `spacing` apart; rings spacing sqrt(3)/2 apart along z, alternate rings
/// turned by half a step). Particles inside touch the wall spheres and the smooth surface
/// through their centres with the contact law `contact` (range_factor as for pairs); the wall
/// spheres move with the wall (their velocity enters damping and friction).
struct RoughCylinder {
    double radius = 10, z_lo = 0, z_hi = 10, omega = 0;
    double spacing = 2.2, sphere_diameter = 1.0;
};
std::unique_ptr<ForceTerm> make_rough_cylinder_wall(const RoughCylinder& wall,
                                                    const GranularPair& contact,
                                                    double range_factor = 1.0);
/// The wall spheres' centres at time t (for pictures and tests), ring by ring.
std::vector<Vec3> rough_cylinder_spheres(const RoughCylinder& wall, double time);

/// A flat end cap of the drum made rough: spheres of diameter `sphere_diameter` embedded with
/// their centres in the plane z = `z`, on a triangular grid of spacing `spacing` fixed in the
/// cap, within `radius` of the axis, turning at `omega` about +z. Particles touch them with
/// the contact law `contact`. (The flat cap itself is a make_plane_wall.)
struct RoughEndCap {
    double z = 0, radius = 10, omega = 0, spacing = 2.2, sphere_diameter = 1.0;
};
std::unique_ptr<ForceTerm> make_rough_end_cap(const RoughEndCap& cap, const GranularPair& contact,
                                              double range_factor = 1.0);
/// The cap's spheres' centres at time t (for pictures and tests).
std::vector<Vec3> rough_end_cap_spheres(const RoughEndCap& cap, double time);

}  // namespace emergent
