// SPDX-License-Identifier: MIT
// Pair forces over a full neighbour list as a per-particle functor: the same code runs as a
// CPU loop (exec::Host) and as one CUDA thread per particle (exec::Cuda), without atomics.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "emergent/vec3.hpp"

namespace emergent::force {

/// Neighbours of i at index[offset[i] .. offset[i+1]): the CPU engine's compressed rows.
struct CompressedNeighbours {
    const std::uint32_t* offset;
    const std::uint32_t* index;
    EMERGENT_HD std::uint32_t count(std::size_t i) const { return offset[i + 1] - offset[i]; }
    EMERGENT_HD std::uint32_t at(std::size_t i, std::uint32_t k) const { return index[offset[i] + k]; }
};

/// Neighbour k of i at index[k * stride + i]: the GPU layout, where the 32 threads of a warp
/// read 32 consecutive words for the same k (one memory transaction instead of 32).
struct StridedNeighbours {
    const std::uint32_t* n;
    const std::uint32_t* index;
    std::size_t stride;
    EMERGENT_HD std::uint32_t count(std::size_t i) const { return n[i]; }
    EMERGENT_HD std::uint32_t at(std::size_t i, std::uint32_t k) const { return index[k * stride + i]; }
};

/// Separation as stored: the CPU engine's periodic images are explicit ghost particles.
struct DirectSeparation {
    EMERGENT_HD Vec3 operator()(const Vec3& d) const { return d; }
};

/// Nearest periodic image in an orthorhombic box (every side at least twice the list cutoff):
/// the single-GPU path keeps no ghosts.
struct MinimumImage {
    Vec3 length, inverse;
    EMERGENT_HD Vec3 operator()(Vec3 d) const {
        d.x -= length.x * rint(d.x * inverse.x);
        d.y -= length.y * rint(d.y * inverse.y);
        d.z -= length.z * rint(d.z * inverse.z);
        return d;
    }
};

/// Sums over some or all of a particle's neighbours: force, energy and virial.
struct PairSums {
    Vec3 f{0, 0, 0};
    Real energy = 0, virial = 0;
    EMERGENT_HD PairSums& operator+=(const PairSums& o) {
        f += o.f;
        energy += o.energy;
        virial += o.virial;
        return *this;
    }
};

/// f[i] = sum over listed j of the evaluator's pair force; writes only f[i]. The separation is
/// formed in double; the evaluator's own type (double, or float in mixed mode) does the rest,
/// and the sum over neighbours is kept in double. With sampling on, energy[i] and virial[i]
/// get half of each pair's energy and r.f (each pair is listed under both members).
/// partial() sums every stride-th neighbour from first, so several GPU threads can share one
/// particle (exec::for_each_split); operator() is the one-thread-per-particle form.
template <class Evaluator, class Neighbours = CompressedNeighbours,
          class Separation = DirectSeparation, bool Sample = false>
struct PairForceFullList {
    using Partial = PairSums;

    const Vec3* x;
    Vec3* f;
    Neighbours neighbours;
    Evaluator eval;
    Separation separation{};
    Real* energy = nullptr;
    Real* virial = nullptr;
    bool accumulate = false;  ///< f[i] += the sum (after other terms) instead of f[i] = it

    EMERGENT_HD PairSums partial(std::size_t i, std::uint32_t first, std::uint32_t stride) const {
        using T = decltype(eval.cutoff_sq);
        const Vec3 xi = x[i];
        PairSums s;
        const std::uint32_t n = neighbours.count(i);
        for (std::uint32_t k = first; k < n; k += stride) {
            const Vec3 d = separation(xi - x[neighbours.at(i, k)]);
            const T dx = T(d.x), dy = T(d.y), dz = T(d.z);
            const T r2 = dx * dx + dy * dy + dz * dz;
            if (r2 < eval.cutoff_sq) {
                const T fr = eval.force_over_r(r2);
                s.f.x += Real(fr * dx);
                s.f.y += Real(fr * dy);
                s.f.z += Real(fr * dz);
                if constexpr (Sample) {
                    s.energy += Real(eval.energy(r2));
                    s.virial += Real(fr * r2);
                }
            }
        }
        return s;
    }

    EMERGENT_HD void store(std::size_t i, const PairSums& s) const {
        f[i] = accumulate ? f[i] + s.f : s.f;
        if constexpr (Sample) {
            energy[i] = 0.5 * s.energy;
            virial[i] = 0.5 * s.virial;
        }
    }

    EMERGENT_HD void operator()(std::size_t i) const { store(i, partial(i, 0, 1)); }
};

}  // namespace emergent::force
