// SPDX-License-Identifier: MIT
// Ghost exchange plan.
#include "halo_exchange.hpp"

#include <cstring>
#include <stdexcept>

#include "field_packing.hpp"
#include "ghost_image.hpp"
#include "message_tally.hpp"

namespace emergent::decomp {

namespace {
constexpr int kCountTag = 7101;
constexpr int kDataTag = 7102;
}  // namespace

void HaloExchange::exchange(const Swap& swap, const void* send, std::size_t send_bytes,
                            void* recv, std::size_t recv_bytes, int tag, MessageCounts& tally) const {
    if (swap.to_self) {
        if (send_bytes) std::memcpy(recv, send, send_bytes);
        return;
    }
    send_receive(send, send_bytes, swap.send_rank, recv, recv_bytes, swap.recv_rank, tag, comm_, tally);
}

void HaloExchange::build(ParticleStore& store, const RankGrid& grid, double width,
                         unsigned fields) {
    fields |= kPosition;
    comm_ = grid.comm();
    exports_elsewhere_ = false;
    store.resize_ghosts(0);
    swaps_.clear();
    const std::size_t stride = packed_bytes(store, fields);
    const Vec3 lo = grid.lo(), hi = grid.hi(), len = grid.global().length();
    wedge_ = grid.global().wedge;
    for (int d = 0; d < 3; ++d) {
        if (d == 2 && wedge_.active()) build_wedge_images(store, width, fields, stride);
        // Both faces of an axis export from the particles present before the axis began,
        // so a ghost imported through -d is not sent straight back through +d.
        const std::size_t n_candidates = store.size();
        for (int side = 0; side < 2; ++side) {
            Swap swap;
            swap.send_rank = grid.neighbour(d, side);
            swap.recv_rank = grid.neighbour(d, 1 - side);
            swap.to_self = swap.send_rank == grid.rank() && swap.recv_rank == grid.rank();
            if (grid.wraps(d, side)) swap.shift[d] = side == 0 ? len[d] : -len[d];
            if (swap.send_rank != MPI_PROC_NULL) {
                for (std::size_t i = 0; i < n_candidates; ++i) {
                    const double x = store.position[i][d];
                    if (side == 0 ? x < lo[d] + width : x >= hi[d] - width)
                        swap.export_index.push_back(static_cast<int>(i));
                }
            }
            unsigned long n_send = swap.export_index.size(), n_recv = 0;
            if (swap.to_self)
                n_recv = n_send;
            else
                send_receive(&n_send, sizeof n_send, swap.send_rank, &n_recv, sizeof n_recv,
                             swap.recv_rank, kCountTag, comm_, build_traffic_);
            send_buffer_.clear();
            pack_fields_shifted(store, fields, swap, stride);
            recv_buffer_.resize(n_recv * stride);
            exchange(swap, send_buffer_.data(), send_buffer_.size(), recv_buffer_.data(),
                     recv_buffer_.size(), kDataTag, build_traffic_);
            swap.import_first = store.size();
            swap.import_count = n_recv;
            store.resize_ghosts(store.n_ghost() + n_recv);
            unpack_fields(store, fields, recv_buffer_.data(), n_recv, swap.import_first);
            swaps_.push_back(std::move(swap));
        }
    }
    n_ghost_ = store.n_ghost();
}

void HaloExchange::build_wedge_images(ParticleStore& store, double width, unsigned fields,
                                      std::size_t stride) {
    // x and y are whole on this rank, so both cut faces are ours: copies from near the face
    // theta = 0 are turned by +1 wedge angle (they appear beyond the other face), copies from
    // near theta = 2 pi / n by -1. Both faces export only particles present before either.
    const std::size_t n_candidates = store.size();
    for (int side = 0; side < 2; ++side) {
        Swap swap;
        swap.send_rank = swap.recv_rank = MPI_PROC_NULL;
        swap.to_self = true;
        swap.turns = side == 0 ? 1 : -1;
        for (std::size_t i = 0; i < n_candidates; ++i) {
            const Vec3& x = store.position[i];
            const double gap = side == 0 ? Wedge::distance_to_first_face(x)
                                         : wedge_.distance_to_second_face(x);
            if (gap < width) swap.export_index.push_back(static_cast<int>(i));
        }
        const std::size_t n = swap.export_index.size();
        send_buffer_.clear();
        pack_fields_shifted(store, fields, swap, stride);
        swap.import_first = store.size();
        swap.import_count = n;
        store.resize_ghosts(store.n_ghost() + n);
        unpack_fields(store, fields, send_buffer_.data(), n, swap.import_first);
        swaps_.push_back(std::move(swap));
    }
}

void HaloExchange::pack_fields_shifted(ParticleStore& store, unsigned fields, const Swap& swap,
                                       std::size_t stride) {
    const std::size_t n = swap.export_index.size();
    pack_fields(store, fields, swap.export_index.data(), n, send_buffer_);
    // Position is the first packed field (velocity, when packed, the second); the copy lands
    // at the image across the boundary.
    const bool velocity = (fields & kVelocity) != 0;
    for (std::size_t k = 0; k < n; ++k) {
        char* record = send_buffer_.data() + k * stride;
        Vec3 x;
        std::memcpy(&x, record, sizeof(Vec3));
        if (swap.turns) x = wedge_.rotate(x, swap.turns);
        x += swap.shift;
        std::memcpy(record, &x, sizeof(Vec3));
        if (velocity && swap.turns) {
            Vec3 v;
            std::memcpy(&v, record + sizeof(Vec3), sizeof(Vec3));
            v = wedge_.rotate(v, swap.turns);
            std::memcpy(record + sizeof(Vec3), &v, sizeof(Vec3));
        }
    }
}

void HaloExchange::adopt_plan(const RankGrid& grid, const std::vector<SwapPlan>& plans) {
    comm_ = grid.comm();
    wedge_ = grid.global().wedge;
    swaps_.clear();
    n_ghost_ = 0;
    // The ranks of each swap as build() finds them, in its order.
    std::size_t k = 0;
    auto take = [&](Swap swap) {
        if (k >= plans.size() || plans[k].to_self != swap.to_self)
            throw std::logic_error("HaloExchange::adopt_plan: the swaps are not build()'s");
        swap.shift = plans[k].shift;
        swap.turns = plans[k].turns;
        swap.import_first = plans[k].import_first;
        swap.import_count = plans[k].import_count;
        n_ghost_ += swap.import_count;
        swaps_.push_back(std::move(swap));
        ++k;
    };
    for (int d = 0; d < 3; ++d) {
        if (d == 2 && wedge_.active())
            for (int side = 0; side < 2; ++side) {
                Swap swap;
                swap.send_rank = swap.recv_rank = MPI_PROC_NULL;
                swap.to_self = true;
                take(std::move(swap));
            }
        for (int side = 0; side < 2; ++side) {
            Swap swap;
            swap.send_rank = grid.neighbour(d, side);
            swap.recv_rank = grid.neighbour(d, 1 - side);
            swap.to_self = swap.send_rank == grid.rank() && swap.recv_rank == grid.rank();
            take(std::move(swap));
        }
    }
    if (k != plans.size()) throw std::logic_error("HaloExchange::adopt_plan: the swaps are not build()'s");
    exports_elsewhere_ = true;
}

void HaloExchange::gather(std::vector<Vec3>& field, bool is_position) {
    if (exports_elsewhere_)
        throw std::logic_error("HaloExchange: this plan's export lists live on the back end");
    for (const Swap& swap : swaps_) {
        const std::size_t n = swap.export_index.size();
        send_vectors_.resize(n);
        const Vec3 offset = is_position ? swap.shift : Vec3{0, 0, 0};
        const GhostImage image{field.data(), swap.export_index.data(), send_vectors_.data(),
                               wedge_, swap.turns, offset};
        for (std::size_t k = 0; k < n; ++k) image(k);
        exchange(swap, send_vectors_.data(), n * sizeof(Vec3), field.data() + swap.import_first,
                 swap.import_count * sizeof(Vec3), kDataTag, refresh_traffic_);
    }
}

HaloExchange::SwapPlan HaloExchange::swap_plan(std::size_t k) const {
    const Swap& s = swaps_.at(k);
    return SwapPlan{s.to_self, s.shift, s.turns, s.import_first, s.import_count};
}

void HaloExchange::exchange_bytes(std::size_t k, const void* send, std::size_t send_bytes,
                                  void* recv, std::size_t recv_bytes) const {
    exchange(swaps_.at(k), send, send_bytes, recv, recv_bytes, kDataTag, refresh_traffic_);
}

}  // namespace emergent::decomp
