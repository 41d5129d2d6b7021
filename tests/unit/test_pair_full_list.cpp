// SPDX-License-Identifier: MIT
// The neighbour loop's two forms give the same forces: its per-particle full-list functor (the
// GPU kernel's body), run here through the host back end of the execution layer, and its
// half-list loop (host code).
#include <gtest/gtest.h>

#include <cmath>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/rank_grid.hpp"
#include "emergent/execution.hpp"
#include "force/lennard_jones.hpp"
#include "emergent/pair_law.hpp"
#include "neighbour/cell_list.hpp"
#include "neighbour/neighbour_list.hpp"
#include "support/random_points.hpp"

using namespace emergent;

TEST(PairFullList, SameForcesAsTheHalfListLoop) {
    // A dense random LJ configuration (rc = 2.5, many pairs per particle) in a periodic box.
    Box box;
    box.hi = {9, 9, 9};
    decomp::RankGrid grid(MPI_COMM_SELF, box);
    ParticleStore store;
    fixtures::add_uniform_particles(store, box.hi, 600, 11);
    const force::LennardJones lj({1.0, 1.0, 2.5});
    NeighbourList list(2.5, 0.3);
    CellList cells;
    cells.setup(grid.lo(), grid.hi(), list.list_cutoff(), list.list_cutoff());
    std::vector<std::uint32_t> order;
    cells.sort_order(store.position.data(), store.id.data(), store.n_owned(), order);
    store.permute_owned(order);
    decomp::HaloExchange halo;
    halo.build(store, grid, list.list_cutoff(), kPosition);
    cells.bin(store.position.data(), store.size());

    list.build(store, cells);
    std::fill(store.force.begin(), store.force.end(), Vec3{0, 0, 0});
    const force::RadialPairLaw<force::LennardJones> law{lj};
    const force::PairArrays half_arrays{store.position.data(), nullptr, nullptr, nullptr, store.force.data(),
                                        list.offsets(), list.neighbours()};
    force::pair_forces_half_list<false>(law, half_arrays, list.n_owned(), 0, list.n_owned());
    const std::vector<Vec3> half(store.force.begin(), store.force.begin() + store.n_owned());

    NeighbourList full(2.5, 0.3);
    full.build_full(store, cells);
    // Owned-ghost pairs appear once in the half list (under the owned member) and once in the
    // full list; owned-owned pairs once and twice. The half list's search runs in single
    // precision with its range widened by the rounding, so it may also hold pairs just beyond
    // the range (harmless: beyond the cutoff); count the pairs within it.
    const double r2 = list.list_cutoff() * list.list_cutoff();
    std::size_t in_range = 0, ghost_pairs = 0, beyond = 0;
    for (std::size_t i = 0; i < list.n_owned(); ++i)
        for (auto k = list.offsets()[i]; k < list.offsets()[i + 1]; ++k) {
            const std::uint32_t j = list.neighbours()[k];
            const Vec3 d = store.position[i] - store.position[j];
            if (dot(d, d) >= r2) {
                ++beyond;
                continue;
            }
            ++in_range;
            ghost_pairs += j >= store.n_owned();
        }
    EXPECT_EQ(full.n_pairs(), 2 * in_range - ghost_pairs);
    EXPECT_LE(beyond, 1e-3 * in_range);  // the widening is ~1e-6 of the range
    std::vector<Vec3> f(store.size(), Vec3{0, 0, 0});
    exec::for_each(exec::Host{}, store.n_owned(),
                   force::PairForcesFullList<force::RadialPairLaw<force::LennardJones>, false>{
                       law, {store.position.data(), nullptr, nullptr, nullptr, f.data(), full.offsets(),
                             full.neighbours()}});
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < store.n_owned(); ++i) {
        const Vec3 d = f[i] - half[i];
        worst = std::max(worst, std::sqrt(dot(d, d)));
        scale = std::max(scale, std::sqrt(dot(half[i], half[i])));
    }
    // Same pair terms summed in another order: round-off only (forces up to ~1e6 at the
    // closest random pairs, so compare relative to the largest force).
    EXPECT_LT(worst, 1e-12 * scale);
    EXPECT_GT(scale, 0);
}
