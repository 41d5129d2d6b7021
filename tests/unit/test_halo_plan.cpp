// SPDX-License-Identifier: MIT
// The halo plan: made by one function from any place's particles; a lone domain's images by kind
// lay out the same plan as its swaps one after another.
#include <gtest/gtest.h>

#include <bitset>
#include <cstdint>
#include <vector>

#include "decomposition/halo_exchange.hpp"
#include "decomposition/halo_plan.hpp"
#include "emergent/particle_store.hpp"

using namespace emergent;
using emergent::decomp::HaloPlan;
using emergent::decomp::RankGrid;
using emergent::decomp::SwapRoute;

namespace {

/// A place that holds no particles: each swap exports `per_swap` and brings as many, so the
/// candidates each swap was offered show the phases.
struct CountingPlace {
    std::size_t n = 100, per_swap = 10;
    std::vector<std::size_t> candidates;
    std::size_t size() const { return n; }
    std::size_t select(const SwapRoute&, std::size_t k, std::size_t n_candidates) {
        EXPECT_EQ(k, candidates.size());
        candidates.push_back(n_candidates);
        return per_swap;
    }
    std::size_t move(const SwapRoute& route, std::size_t, std::size_t n_export) {
        const std::size_t n_recv = route.to_self || route.talks() ? n_export : 0;
        n += n_recv;
        return n_recv;
    }
};

/// Random particles in a box, owned by one rank.
ParticleStore scattered(const Box& box, int count) {
    ParticleStore store;
    std::uint64_t state = 12345;
    auto uniform = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    const Vec3 len = box.length();
    for (int k = 0; k < count; ++k)
        store.add_owned({box.lo.x + len.x * uniform(), box.lo.y + len.y * uniform(), box.lo.z + len.z * uniform()},
                        {0, 0, 0}, 0, k);
    return store;
}

}  // namespace

TEST(HaloPlan, BothFacesOfAPhaseChooseFromWhatWasThereWhenItBegan) {
    Box box;
    box.hi = {10, 10, 10};
    RankGrid grid(MPI_COMM_SELF, box);
    CountingPlace place;
    const HaloPlan plan = decomp::make_halo_plan(grid, place);
    // Six swaps, each bringing 10: x's two faces choose from the 100 owned, y's from 120, z's
    // from 140.
    ASSERT_EQ(plan.swaps.size(), 6u);
    EXPECT_EQ(place.candidates, (std::vector<std::size_t>{100, 100, 120, 120, 140, 140}));
    EXPECT_EQ(plan.n_owned, 100u);
    EXPECT_EQ(plan.n_ghost, 60u);
    for (std::size_t k = 0; k < 6; ++k) {
        EXPECT_EQ(plan.swaps[k].import_first, 100 + 10 * k) << k;
        EXPECT_EQ(plan.swaps[k].route.axis, static_cast<int>(k / 2)) << k;
        EXPECT_EQ(plan.swaps[k].route.side, static_cast<int>(k % 2)) << k;
    }
    EXPECT_TRUE(plan.from_roots());
}

TEST(HaloPlan, ALoneDomainHasAKindOfImageForEveryFaceEdgeAndCorner) {
    Box box;
    box.hi = {10, 10, 10};
    RankGrid periodic(MPI_COMM_SELF, box);
    ASSERT_TRUE(decomp::lone_domain(periodic));
    const decomp::LoneDomainImages all = decomp::lone_domain_images(periodic);
    // 3^3 - 1 kinds, each near one face per axis at most, no two alike; the x swaps make the
    // kinds of x alone, y's those with a y face, z's those with a z face.
    ASSERT_EQ(all.kinds.size(), 26u);
    EXPECT_EQ(all.first_kind, (std::vector<std::size_t>{0, 1, 2, 5, 8, 17, 26}));
    std::vector<unsigned> seen;
    for (std::size_t q = 0; q < all.kinds.size(); ++q) {
        const unsigned faces = all.kinds[q].faces;
        for (int d = 0; d < 3; ++d) EXPECT_NE(faces >> (2 * d) & 3u, 3u) << q;
        for (unsigned other : seen) EXPECT_NE(faces, other) << q;
        seen.push_back(faces);
        // The shift takes the image across every face it is near: +L from a low face.
        for (int d = 0; d < 3; ++d) {
            const double expected = (faces >> (2 * d) & 1u) ? 10.0 : (faces >> (2 * d) & 2u) ? -10.0 : 0.0;
            EXPECT_EQ(all.kinds[q].shift[d], expected) << q << " axis " << d;
        }
    }
    // Walls along z: faces and edges of x and y only.
    Box layer = wall_bounded_layer(10, 10, 8);
    RankGrid walled(MPI_COMM_SELF, layer);
    ASSERT_TRUE(decomp::lone_domain(walled));
    EXPECT_EQ(decomp::lone_domain_images(walled).kinds.size(), 8u);
}

TEST(HaloPlan, ALoneDomainsImagesByKindLayOutTheSwapsPlan) {
    // The host's build, swap after swap, against the plan laid out from each kind's count
    // (counted here by brute force: a particle makes an image of every kind whose faces it is
    // near).
    for (bool walls : {false, true}) {
        Box box = walls ? wall_bounded_layer(9, 8, 7) : Box{};
        if (!walls) box.hi = {9, 8, 7};
        RankGrid grid(MPI_COMM_SELF, box);
        ParticleStore store = scattered(box, 2000);
        const double width = 1.7;
        decomp::HaloExchange halo;
        halo.build(store, grid, width, kPosition);
        const decomp::LoneDomainImages images = decomp::lone_domain_images(grid);
        std::vector<std::size_t> count(images.kinds.size(), 0);
        for (std::size_t i = 0; i < store.n_owned(); ++i) {
            unsigned near = 0;
            for (int d = 0; d < 3; ++d) {
                if (!box.periodic[d]) continue;
                if (store.position[i][d] < grid.lo()[d] + width) near |= 1u << (2 * d);
                if (store.position[i][d] >= grid.hi()[d] - width) near |= 2u << (2 * d);
            }
            for (std::size_t q = 0; q < images.kinds.size(); ++q)
                count[q] += (near & images.kinds[q].faces) == images.kinds[q].faces;
        }
        const HaloPlan laid_out = images.plan(store.n_owned(), count);
        const HaloPlan& made = halo.plan();
        ASSERT_EQ(laid_out.swaps.size(), made.swaps.size()) << walls;
        EXPECT_EQ(laid_out.n_ghost, made.n_ghost) << walls;
        EXPECT_GT(made.n_ghost, store.n_owned() / 2) << walls;
        for (std::size_t k = 0; k < made.swaps.size(); ++k) {
            EXPECT_EQ(laid_out.swaps[k].import_first, made.swaps[k].import_first) << walls << " swap " << k;
            EXPECT_EQ(laid_out.swaps[k].import_count, made.swaps[k].import_count) << walls << " swap " << k;
            EXPECT_EQ(laid_out.swaps[k].export_count, made.swaps[k].export_count) << walls << " swap " << k;
        }
    }
}
