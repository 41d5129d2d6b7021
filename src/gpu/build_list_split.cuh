// SPDX-License-Identifier: MIT
// The full-list build with several threads per particle: the lanes of a tile test consecutive
// candidates together and place the hits in candidate order (ballot and population count), so
// the list is the same as BuildFullList's one-thread build, entry for entry.
#pragma once

#include <cooperative_groups.h>

#include "emergent/cuda_launch.cuh"
#include "gpu/device_cells.hpp"

namespace emergent::gpu {

template <int Lanes>
__global__ void build_list_split_kernel(std::size_t n, BuildFullList b) {
    namespace cg = cooperative_groups;
    const auto tile = cg::tiled_partition<Lanes>(cg::this_thread_block());
    const std::size_t i = (blockIdx.x * static_cast<std::size_t>(blockDim.x) + threadIdx.x) / Lanes;
    if (i >= n) return;  // the whole tile shares i, so it leaves together
    const unsigned lane = tile.thread_rank();
    const unsigned below = lane == 0 ? 0u : (0xffffffffu >> (32 - lane));  // lanes before this one
    const Vec3 xi = b.x[i];
    std::uint32_t k = 0;
    const Int3 ci = b.grid.cell_of(xi);
    for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const std::uint32_t cell = b.nearby_cell(ci, dx, dy, dz);
                const std::uint32_t last = b.end[cell];
                for (std::uint32_t base = b.start[cell]; base < last; base += Lanes) {
                    const std::uint32_t j = base + lane;
                    const bool hit = j < last && b.is_neighbour(i, xi, j);
                    const unsigned hits = tile.ballot(hit);
                    if (hit) b.put(i, k + __popc(hits & below), j);
                    k += __popc(hits);
                }
            }
    if (lane == 0) b.count[i] = k;
}

/// Builds the list with `lanes` threads per particle (1 runs the functor itself).
inline void build_list_split(exec::Cuda backend, std::size_t n, int lanes, const BuildFullList& b) {
    if (lanes == 1) return exec::for_each(backend, n, b);
    if (n == 0) return;
    exec::with_lanes(lanes, [&](auto width) {
        build_list_split_kernel<decltype(width)::value>
            <<<exec::blocks_for(backend, n, lanes), backend.block_size, 0, backend.stream>>>(n, b);
    });
    EMERGENT_CUDA_CHECK(cudaGetLastError());
}

}  // namespace emergent::gpu
