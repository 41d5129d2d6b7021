// SPDX-License-Identifier: MIT
// The halo's routes in their order, and a lone domain's ghosts by kind.
#include "halo_plan.hpp"

#include <stdexcept>

namespace emergent::decomp {

std::vector<SwapRoute> halo_routes(const RankGrid& grid) {
    std::vector<SwapRoute> routes;
    const Vec3 len = grid.global().length();
    for (int d = 0; d < 3; ++d) {
        if (d == 2 && grid.global().wedge.active())
            for (int side = 0; side < 2; ++side) {
                SwapRoute cut;
                cut.axis = -1;
                cut.side = side;
                cut.to_self = true;
                cut.turns = side == 0 ? 1 : -1;
                cut.starts_phase = side == 0;
                routes.push_back(cut);
            }
        for (int side = 0; side < 2; ++side) {
            SwapRoute face;
            face.axis = d;
            face.side = side;
            face.send_rank = grid.neighbour(d, side);
            face.recv_rank = grid.neighbour(d, 1 - side);
            face.to_self = face.send_rank == grid.rank() && face.recv_rank == grid.rank();
            if (grid.wraps(d, side)) face.shift[d] = side == 0 ? len[d] : -len[d];
            face.starts_phase = side == 0;
            routes.push_back(face);
        }
    }
    return routes;
}

bool HaloPlan::from_roots() const {
    // Faces -x, +x, -y, +y, -z, +z: the two swaps of an axis never re-export each other's
    // ghosts (a wedge adds two swaps: not here).
    if (swaps.size() != 6) return false;
    for (std::size_t k = 0; k < 6; ++k) {
        const SwapRoute& route = swaps[k].route;
        if (!route.to_self || route.turns != 0) return false;
        for (int d = 0; d < 3; ++d)
            if (d != static_cast<int>(k / 2) && route.shift[d] != 0) return false;
    }
    return true;
}

bool lone_domain(const RankGrid& grid) {
    if (grid.size() != 1 || grid.global().wedge.active()) return false;
    for (const SwapRoute& route : halo_routes(grid))
        if (route.axis < 0 || route.turns != 0 || route.talks()) return false;
    return true;
}

LoneDomainImages lone_domain_images(const RankGrid& grid) {
    if (!lone_domain(grid)) throw std::logic_error("lone_domain_images: the domain is not alone");
    LoneDomainImages images;
    images.routes = halo_routes(grid);
    images.wedge = grid.global().wedge;
    // Kind 0 stands for the owned particles; route k images every kind present when its phase
    // began, adding its face.
    std::vector<LoneDomainImages::Kind> made(1);
    std::size_t present = 1;
    for (const SwapRoute& route : images.routes) {
        if (route.starts_phase) present = made.size();
        images.first_kind.push_back(made.size() - 1);
        if (!route.to_self) continue;  // a wall
        for (std::size_t p = 0; p < present; ++p)
            made.push_back({made[p].faces | 1u << (2 * route.axis + route.side), made[p].shift + route.shift});
    }
    images.first_kind.push_back(made.size() - 1);
    images.kinds.assign(made.begin() + 1, made.end());
    return images;
}

HaloPlan LoneDomainImages::plan(std::size_t n_owned, const std::vector<std::size_t>& count) const {
    if (count.size() != kinds.size()) throw std::logic_error("LoneDomainImages::plan: a count per kind");
    HaloPlan plan;
    plan.wedge = wedge;
    plan.n_owned = n_owned;
    std::size_t next = n_owned;
    for (std::size_t k = 0; k < routes.size(); ++k) {
        HaloSwap swap{routes[k], 0, next, 0};
        for (std::size_t q = first_kind[k]; q < first_kind[k + 1]; ++q) swap.import_count += count[q];
        // A copy to itself sends what it brings.
        swap.export_count = swap.import_count;
        next += swap.import_count;
        plan.swaps.push_back(swap);
    }
    plan.n_ghost = next - n_owned;
    return plan;
}

}  // namespace emergent::decomp
