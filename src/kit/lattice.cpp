// SPDX-License-Identifier: MIT
// Lattice filling.
#include "emergent/kit/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "emergent/error.hpp"
#include "emergent/random.hpp"

#include "emergent/simulation.hpp"

namespace emergent {

namespace {
template <class Visit>
void for_each_point(const Vec3& lo, const Vec3& hi, const Vec3& spacing, Visit&& visit) {
    int n[3];
    // A hair of tolerance: a tiling spacing must give exactly length / spacing cells.
    for (int d = 0; d < 3; ++d)
        n[d] = static_cast<int>(std::floor((hi[d] - lo[d]) / spacing[d] * (1 + 1e-12)));
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                visit(lo + Vec3{spacing.x * (i + 0.5), spacing.y * (j + 0.5), spacing.z * (k + 0.5)});
}

Vec3 spacing_for(double a, const Vec3& lo, const Vec3& hi, const bool periodic[3]) {
    Vec3 s{a, a, a};
    for (int d = 0; d < 3; ++d)
        if (periodic[d]) s[d] = tiling_spacing(hi[d] - lo[d], a);
    return s;
}
}  // namespace

std::int64_t count_cubic_lattice(const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                 const std::function<bool(const Vec3&)>& inside) {
    std::int64_t count = 0;
    for_each_point(lo, hi, spacing, [&](const Vec3& x) { count += inside(x) ? 1 : 0; });
    return count;
}

Vec3 spacing_for_count(const Vec3& lo, const Vec3& hi, std::int64_t target, const bool periodic[3],
                       const std::function<bool(const Vec3&)>& inside) {
    // The count falls in steps as the spacing grows: bracket the target, then bisect, and
    // keep the spacing whose count came closest.
    const Vec3 l = hi - lo;
    auto count = [&](double a) {
        return count_cubic_lattice(lo, hi, spacing_for(a, lo, hi, periodic), inside);
    };
    double a = std::cbrt(l.x * l.y * l.z / std::max<std::int64_t>(target, 1));
    double dense = a, sparse = a;  // count(dense) >= target > count(sparse)
    while (count(dense) < target && dense > 1e-3 * a) dense *= 0.9;
    while (count(sparse) >= target && sparse < 1e3 * a) sparse *= 1.1;
    double best_a = dense;
    std::int64_t best = count(dense);
    for (int k = 0; k < 40 && std::llabs(best - target) > target / 1000; ++k) {
        const double mid = 0.5 * (dense + sparse);
        const std::int64_t n = count(mid);
        if (std::llabs(n - target) < std::llabs(best - target)) best = n, best_a = mid;
        (n >= target ? dense : sparse) = mid;
    }
    return spacing_for(best_a, lo, hi, periodic);
}

std::vector<Vec3> cubic_lattice_points(const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                       const std::function<bool(const Vec3&)>& inside) {
    std::vector<Vec3> points;
    for_each_point(lo, hi, spacing, [&](const Vec3& x) {
        if (inside(x)) points.push_back(x);
    });
    return points;
}

std::int64_t fill_lattice_with_count(Simulation& sim, const Vec3& lo, const Vec3& hi,
                                     std::int64_t target, const bool periodic[3],
                                     const std::function<bool(const Vec3&)>& inside) {
    return fill_cubic_lattice(sim, lo, hi, spacing_for_count(lo, hi, target, periodic, inside),
                              inside);
}

std::int64_t fill_cubic_lattice(Simulation& sim, const Vec3& lo, const Vec3& hi, const Vec3& spacing,
                                const std::function<bool(const Vec3&)>& inside,
                                std::int64_t first_id) {
    int n[3];
    // A hair of tolerance: a tiling spacing must give exactly length / spacing cells.
    for (int d = 0; d < 3; ++d)
        n[d] = static_cast<int>(std::floor((hi[d] - lo[d]) / spacing[d] * (1 + 1e-12)));
    std::int64_t id = first_id;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                const Vec3 x = lo + Vec3{spacing.x * (i + 0.5), spacing.y * (j + 0.5),
                                         spacing.z * (k + 0.5)};
                if (!inside(x)) continue;
                sim.add_particle(x, {0, 0, 0}, 0, id++);
            }
    return id - first_id;
}

std::int64_t fill_wall_bounded_layer(Simulation& sim, double lx, double ly, double height,
                                     double density) {
    const auto target = static_cast<std::int64_t>(std::llround(density * lx * ly * height));
    const bool periodic[3] = {true, true, false};
    return fill_lattice_with_count(sim, {0, 0, 0}, {lx, ly, height}, target, periodic,
                                   [](const Vec3&) { return true; });
}

std::vector<Vec3> random_sequential_packing(const Vec3& lo, const Vec3& hi,
                                            const std::vector<double>& diameters, double range,
                                            std::uint64_t seed,
                                            const std::function<bool(const Vec3&, double)>& inside,
                                            int tries) {
    double d_max = 0;
    for (double d : diameters) d_max = std::max(d_max, d);
    // Cells no narrower than the largest contact distance: overlaps lie in the 27 around.
    const double cell = std::max(range * d_max, 1e-9);
    long n[3];
    for (int a = 0; a < 3; ++a) n[a] = std::max(1L, static_cast<long>(std::floor((hi[a] - lo[a]) / cell)));
    auto index = [&](const Vec3& x, int a) {
        const long k = static_cast<long>(std::floor((x[a] - lo[a]) / (hi[a] - lo[a]) * n[a]));
        return std::min(std::max(k, 0L), n[a] - 1);
    };
    std::vector<std::vector<std::uint32_t>> cells(static_cast<std::size_t>(n[0] * n[1] * n[2]));
    std::vector<Vec3> placed;
    placed.reserve(diameters.size());
    for (std::size_t i = 0; i < diameters.size(); ++i) {
        const double d = diameters[i];
        bool done = false;
        for (int t = 0; t < tries && !done; ++t) {
            // Draws keyed by sphere and attempt: the same sequence on every rank.
            const std::uint64_t key = (static_cast<std::uint64_t>(i) << 20) ^ static_cast<std::uint64_t>(t);
            const Vec3 x{lo.x + (hi.x - lo.x) * uniform_open(seed, key, 0),
                         lo.y + (hi.y - lo.y) * uniform_open(seed, key, 1),
                         lo.z + (hi.z - lo.z) * uniform_open(seed, key, 2)};
            if (!inside(x, d)) continue;
            const long c[3] = {index(x, 0), index(x, 1), index(x, 2)};
            bool free = true;
            for (long kz = std::max(0L, c[2] - 1); free && kz <= std::min(n[2] - 1, c[2] + 1); ++kz)
                for (long ky = std::max(0L, c[1] - 1); free && ky <= std::min(n[1] - 1, c[1] + 1); ++ky)
                    for (long kx = std::max(0L, c[0] - 1); free && kx <= std::min(n[0] - 1, c[0] + 1); ++kx)
                        for (std::uint32_t j : cells[static_cast<std::size_t>((kz * n[1] + ky) * n[0] + kx)]) {
                            const Vec3 r = x - placed[j];
                            const double reach = 0.5 * range * (d + diameters[j]);
                            if (dot(r, r) < reach * reach) {
                                free = false;
                                break;
                            }
                        }
            if (!free) continue;
            cells[static_cast<std::size_t>((c[2] * n[1] + c[1]) * n[0] + c[0])].push_back(
                static_cast<std::uint32_t>(placed.size()));
            placed.push_back(x);
            done = true;
        }
        if (!done)
            throw InputError("random packing: sphere " + std::to_string(i) + " of " +
                             std::to_string(diameters.size()) + " found no free place in " +
                             std::to_string(tries) + " tries (the region is too full)");
    }
    return placed;
}

}  // namespace emergent

