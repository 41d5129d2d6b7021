// SPDX-License-Identifier: MIT
// A new pair law as docs/plugins.md shows it: a soft harmonic repulsion (the worked example's
// law at r_c = 1, a = eps) written as one evaluator and made a force term by make_pair_term
// (emergent/pair_law.hpp). Its forces are minus the gradient of its energy (central
// differences), the half list's and the full list's agree, and the pairs' forces cancel.
#include <gtest/gtest.h>

#include <cmath>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/execution.hpp"
#include "emergent/pair_law.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/neighbour_list.hpp"
#include "support/random_points.hpp"

using namespace emergent;

namespace {
// --- the law ---
/// u(r) = eps/2 (1 - r/sigma)^2 for r < sigma: soft spheres that may overlap (a DPD-like
/// conservative repulsion).
struct SoftSphere {
    Real eps = 1, sigma = 1, cutoff_sq = 1;
    SoftSphere(Real e, Real s) : eps(e), sigma(s), cutoff_sq(s * s) {}
    /// |f| / r at squared distance r2 (< cutoff_sq): f = -du/dr = eps/sigma (1 - r/sigma).
    EMERGENT_HD Real force_over_r(Real r2) const {
        const Real r = std::sqrt(r2);
        return eps / sigma * (1 - r / sigma) / r;
    }
    EMERGENT_HD Real energy(Real r2) const {
        const Real x = 1 - std::sqrt(r2) / sigma;
        return Real(0.5) * eps * x * x;
    }
};
std::unique_ptr<ForceTerm> make_soft_spheres(double eps, double sigma) {
    return make_pair_term("soft-spheres", SoftSphere(eps, sigma), sigma);
}
// --- end of the law ---

/// A periodic box of overlapping soft spheres, its list built (half or full) on one rank.
struct Fixture {
    Box box;
    decomp::RankGrid grid;
    ParticleStore store;
    NeighbourList list{1.0, 0.3};
    CellList cells;
    decomp::HaloExchange halo;
    Fixture() : box(make_box()), grid(MPI_COMM_SELF, box) {
        fixtures::add_uniform_particles(store, box.hi, 300, 5);
        cells.setup(grid.lo(), grid.hi(), list.list_cutoff(), list.list_cutoff());
        std::vector<std::uint32_t> order;  // the list's search expects cell order
        cells.sort_order(store.position.data(), store.id.data(), store.n_owned(), order);
        store.permute_owned(order);
    }
    static Box make_box() {
        Box b;
        b.hi = {5, 5, 5};
        return b;
    }
    /// Ghosts and list for the current positions.
    void build(bool full) {
        store.resize_owned(store.n_owned());
        halo.build(store, grid, list.list_cutoff(), kPosition);
        cells.bin(store.position.data(), store.size());
        if (full)
            list.build_full(store, cells);
        else
            list.build(store, cells);
    }
    /// Forces and sampled energy through the term's host form (half list).
    double energy(const ForceTerm& term) {
        build(false);
        std::fill(store.force.begin(), store.force.end(), Vec3{0, 0, 0});
        ForceSums sums;
        term.add_forces(store, list, ForceContext{}, true, sums);
        return sums.potential;
    }
};
}  // namespace

TEST(NewPairLaw, ForceIsMinusTheGradientOfTheEnergy) {
    Fixture s;
    const auto term = make_soft_spheres(25.0, 1.0);
    s.energy(*term);
    const std::vector<Vec3> force(s.store.force.begin(), s.store.force.begin() + s.store.n_owned());
    // Central differences of the total energy; u is smooth inside the cutoff and C1 at it, so
    // the error is O(h^2 u''') ~ 1e-8 here, against forces of order 10 (eps 25 at overlaps ~0.5).
    const double h = 1e-5;
    double worst = 0;
    for (std::size_t i = 0; i < 20; ++i)
        for (int d = 0; d < 3; ++d) {
            const Vec3 x0 = s.store.position[i];
            s.store.position[i][d] = x0[d] + h;
            const double up = s.energy(*term);
            s.store.position[i][d] = x0[d] - h;
            const double down = s.energy(*term);
            s.store.position[i] = x0;
            worst = std::max(worst, std::abs(-(up - down) / (2 * h) - force[i][d]));
        }
    EXPECT_LT(worst, 1e-5);
    double largest = 0;
    for (const Vec3& f : force) largest = std::max(largest, std::sqrt(dot(f, f)));
    EXPECT_GT(largest, 1.0);  // the configuration does overlap: the check is not of zeros
}

TEST(NewPairLaw, HalfAndFullListsAgreeAndForcesCancel) {
    Fixture s;
    const auto term = make_soft_spheres(25.0, 1.0);
    s.energy(*term);
    const std::size_t n = s.store.n_owned();
    const std::vector<Vec3> half(s.store.force.begin(), s.store.force.begin() + n);
    // On one rank a pair across the periodic boundary is listed under both members, each with
    // the other's image: the owned particles take both sides of every pair, so their forces
    // cancel (round-off of forces ~10 over 300 particles).
    Vec3 total{0, 0, 0};
    for (const Vec3& f : half) total += f;
    EXPECT_LT(std::sqrt(dot(total, total)), 1e-9);

    s.build(true);
    std::fill(s.store.force.begin(), s.store.force.end(), Vec3{0, 0, 0});
    BackendParticles p;
    p.position = s.store.position.data();
    p.force = s.store.force.data();
    p.n_owned = n;
    p.size = s.store.size();
    p.list_offset = s.list.offsets();
    p.list_index = s.list.neighbours();
    std::vector<Real> energy(n), virial(n);
    p.energy = energy.data();
    p.virial = virial.data();
    ForceContext context;
    ForceSums sums;
    term->add_forces_on_backend(p, context, true, sums);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3 d = s.store.force[i] - half[i];
        worst = std::max(worst, std::sqrt(dot(d, d)));
    }
    EXPECT_LT(worst, 1e-10);  // the same pairs summed in another order
}
