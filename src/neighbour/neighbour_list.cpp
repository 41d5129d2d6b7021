// SPDX-License-Identifier: MIT
// Half Verlet list from a cell list.
#include "neighbour_list.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "emergent/error.hpp"

namespace emergent {

void NeighbourList::build(const ParticleStore& store, const CellList& cells) {
    const std::size_t n_owned = store.n_owned();
    const double r2max = list_cutoff() * list_cutoff();
    const Vec3* x = store.position.data();
    const Int3 shape = cells.shape();
    // Precondition (the engine sorts owned particles by cell before each build): the list is
    // stored in order of i, and inner cells earlier than i's cell hold only smaller indices.
    for (std::size_t i = 1; i < n_owned; ++i)
        if (cells.cell_of(x[i]) < cells.cell_of(x[i - 1]))
            throw std::logic_error("NeighbourList::build: owned particles not sorted by cell");
    offset_.assign(n_owned + 1, 0);
    neighbour_.clear();
    // Owned particles are sorted by cell, so walking inner cells in order visits i ascending.
    for (int cz = 0; cz < shape.z; ++cz)
        for (int cy = 0; cy < shape.y; ++cy)
            for (int cx = 0; cx < shape.x; ++cx) {
                const int c = (cz * shape.y + cy) * shape.x + cx;
                if (!cells.is_inner(c)) continue;
                for (const std::uint32_t* pi = cells.members_begin(c); pi != cells.members_end(c);
                     ++pi) {
                    const std::uint32_t i = *pi;
                    const Vec3 xi = x[i];
                    for (int dz = -1; dz <= 1; ++dz)
                        for (int dy = -1; dy <= 1; ++dy)
                            for (int dx = -1; dx <= 1; ++dx) {
                                const int c2 = ((cz + dz) * shape.y + cy + dy) * shape.x + cx + dx;
                                // Inner cells before c hold only owned j < i.
                                if (c2 < c && cells.is_inner(c2)) continue;
                                for (const std::uint32_t* pj = cells.members_begin(c2);
                                     pj != cells.members_end(c2); ++pj) {
                                    const std::uint32_t j = *pj;
                                    if (j <= i) continue;
                                    const Vec3 r = xi - x[j];
                                    if (dot(r, r) < r2max) neighbour_.push_back(j);
                                }
                            }
                    offset_[i + 1] = static_cast<std::uint32_t>(neighbour_.size());
                }
            }
    built_at_.assign(store.position.begin(), store.position.begin() + n_owned);
}

double NeighbourList::max_displacement_sq(const ParticleStore& store) const {
    double worst = 0;
    const Vec3* x = store.position.data();
    for (std::size_t i = 0; i < built_at_.size(); ++i) {
        const Vec3 r = x[i] - built_at_[i];
        const double r2 = dot(r, r);
        // Written so that a NaN wins the comparison and is reported.
        if (!(r2 <= worst)) worst = std::isnan(r2) ? std::numeric_limits<double>::quiet_NaN() : r2;
        if (std::isnan(worst)) break;
    }
    return worst;
}

bool NeighbourList::needs_rebuild(const ParticleStore& store, MPI_Comm comm) const {
    double local = max_displacement_sq(store);
    // NaN is mapped to +inf so the MPI max carries it to every rank.
    if (std::isnan(local)) local = std::numeric_limits<double>::infinity();
    double global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm);
    if (std::isinf(global))
        throw InstabilityError("non-finite particle position: the run went unstable "
                               "(time step too large, overlapping start, or forces too strong)");
    // The list is rebuilt as soon as some particle passes skin/2, so a displacement beyond
    // the whole ghost shell means one step jumped further than any pair range: a blow-up.
    if (global > list_cutoff() * list_cutoff()) {
        std::ostringstream msg;
        msg << "a particle moved " << std::sqrt(global) << " sigma within one step, more than "
            << "cutoff + skin = " << list_cutoff()
            << ": the run went unstable (time step too large or forces too strong)";
        throw InstabilityError(msg.str());
    }
    return global > 0.25 * skin_ * skin_;
}

}  // namespace emergent
