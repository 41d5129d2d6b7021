// SPDX-License-Identifier: MIT
// A reproducible start for periodic fluid tests: an fcc lattice jittered by a small random
// displacement, Maxwell velocities at temperature T with zero total momentum.
#pragma once

#include <cmath>
#include <vector>

#include "emergent/random.hpp"
#include "emergent/vec3.hpp"

namespace emergent::fixtures {

struct FluidStart {
    Vec3 box;
    std::vector<Vec3> x, v;
};

inline FluidStart fcc_fluid(int cells, double density, double temperature, double jitter,
                            std::uint64_t seed) {
    FluidStart s;
    const double a = std::cbrt(4 / density);
    const double L = cells * a;
    s.box = {L, L, L};
    const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j)
            for (int k = 0; k < cells; ++k)
                for (const Vec3& b : basis) {
                    const std::uint64_t n = s.x.size();
                    Vec3 p{(i + b.x) * a, (j + b.y) * a, (k + b.z) * a};
                    for (int d = 0; d < 3; ++d) {
                        p[d] += jitter * (uniform_open(seed, n, d) - 0.5);
                        p[d] -= L * std::floor(p[d] / L);
                    }
                    s.x.push_back(p);
                }
    Vec3 mean{0, 0, 0};
    for (std::uint64_t n = 0; n < s.x.size(); ++n) {
        const double sd = std::sqrt(temperature);
        s.v.push_back({sd * gaussian(seed + 1, n, 0), sd * gaussian(seed + 1, n, 1), sd * gaussian(seed + 1, n, 2)});
        mean += s.v.back();
    }
    mean *= 1.0 / double(s.x.size());
    for (Vec3& u : s.v) u -= mean;
    return s;
}

}  // namespace emergent::fixtures
