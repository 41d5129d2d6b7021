// SPDX-License-Identifier: MIT
// Ghost exchange plan.
#include "halo_exchange.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "field_packing.hpp"
#include "ghost_image.hpp"
#include "message_tally.hpp"

namespace emergent::decomp {

namespace {
constexpr int kCountTag = 7101;
constexpr int kDataTag = 7102;
constexpr int kRefreshTag = 7300;  // + 2 swap + field: staged refreshes
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

void HaloExchange::exchange(const Swap& swap, const void* send, std::size_t send_bytes,
                            void* recv, std::size_t recv_bytes, int tag, MessageCounts& tally) const {
    if (swap.to_self) {
        if (send_bytes) std::memcpy(recv, send, send_bytes);
        return;
    }
    send_receive(send, send_bytes, swap.send_rank, recv, recv_bytes, swap.recv_rank, tag, comm_, tally);
}

std::size_t HaloExchange::stage_end(std::size_t first) const {
    // Ghosts are appended swap after swap: a swap depends on the stage if it exports an index
    // at or beyond the stage's first import.
    const std::size_t imports_from = swaps_.at(first).import_first;
    std::size_t k = first + 1;
    for (; k < swaps_.size(); ++k) {
        const std::vector<int>& e = swaps_[k].export_index;
        if (!e.empty() && static_cast<std::size_t>(*std::max_element(e.begin(), e.end())) >= imports_from) break;
    }
    return k;
}

bool HaloExchange::sends_messages(std::size_t first, std::size_t end) const {
    for (std::size_t k = first; k < end; ++k) {
        const Swap& swap = swaps_[k];
        if (!swap.to_self && (swap.send_rank != MPI_PROC_NULL || swap.recv_rank != MPI_PROC_NULL)) return true;
    }
    return false;
}

std::size_t HaloExchange::refresh_stages() const {
    std::size_t stages = 0;
    for (std::size_t k = 0, end; k < swaps_.size(); k = end) {
        end = stage_end(k);
        if (sends_messages(k, end)) ++stages;
    }
    return std::max<std::size_t>(stages, 1);
}

void HaloExchange::begin_refresh(ParticleStore& store, bool velocities) {
    if (exports_elsewhere_)
        throw std::logic_error("HaloExchange: this plan's export lists live on the back end");
    if (staged_position_) throw std::logic_error("HaloExchange::begin_refresh: a refresh is in flight");
    staged_position_ = &store.position;
    staged_velocity_ = velocities ? &store.velocity : nullptr;
    next_swap_ = 0;
    stage_send_.resize(2 * swaps_.size());
    post_stage();
}

void HaloExchange::post_stage() {
    // Stages that only copy (a rank's own periodic images) or face no rank complete at once:
    // they are done here, so that every stage the caller computes across has messages.
    do {
        wait_stage();
        if (next_swap_ >= swaps_.size()) return;
        post_one_stage();
    } while (!sends_messages(stage_begin_, next_swap_));
}

void HaloExchange::post_one_stage() {
    stage_begin_ = next_swap_;
    const std::size_t end = stage_end(next_swap_);
    for (std::size_t k = next_swap_; k < end; ++k) {
        const Swap& swap = swaps_[k];
        for (int field = 0; field < 2; ++field) {
            std::vector<Vec3>* values = field == 0 ? staged_position_ : staged_velocity_;
            if (!values) continue;
            std::vector<Vec3>& out = stage_send_[2 * k + field];
            const std::size_t n = swap.export_index.size();
            out.resize(n);
            const GhostImage image{values->data(), swap.export_index.data(), out.data(), wedge_, swap.turns,
                                   field == 0 ? swap.shift : Vec3{0, 0, 0}};
            for (std::size_t i = 0; i < n; ++i) image(i);
            Vec3* into = values->data() + swap.import_first;
            if (swap.to_self) {
                if (n) std::memcpy(into, out.data(), n * sizeof(Vec3));
                continue;
            }
            // A tag per swap and field: the two faces of an axis may have the same neighbour.
            const int tag = kRefreshTag + static_cast<int>(2 * k) + field;
            // Poisoned until the message lands: a ghost read too early is NaN (its pair is
            // dropped or its force is NaN), never the last step's value, so a missing wait
            // changes the result on every run (tests/mpi/halo_overlap.sh) whatever the timing.
            std::fill(into, into + swap.import_count, Vec3{kNaN, kNaN, kNaN});
            requests_.emplace_back();
            MPI_Irecv(into, static_cast<int>(swap.import_count * sizeof(Vec3)), MPI_BYTE, swap.recv_rank, tag,
                      comm_, &requests_.back());
            requests_.emplace_back();
            MPI_Isend(out.data(), static_cast<int>(n * sizeof(Vec3)), MPI_BYTE, swap.send_rank, tag, comm_,
                      &requests_.back());
            if (swap.send_rank != MPI_PROC_NULL) {
                ++refresh_traffic_.messages;
                refresh_traffic_.bytes += static_cast<long long>(n * sizeof(Vec3));
            }
        }
    }
    next_swap_ = end;
}

void HaloExchange::wait_stage() {
    if (requests_.empty()) return;
    const double start = MPI_Wtime();
    MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    wait_seconds_ += MPI_Wtime() - start;
    requests_.clear();
}

void HaloExchange::progress() {
    if (requests_.empty()) return;
    int done = 0;
    MPI_Testall(static_cast<int>(requests_.size()), requests_.data(), &done, MPI_STATUSES_IGNORE);
}

void HaloExchange::advance_refresh() {
    if (!staged_position_) return;
    post_stage();  // waits for the stage in flight first
}

void HaloExchange::end_refresh() {
    if (!staged_position_) return;
    while (next_swap_ < swaps_.size()) post_stage();
    wait_stage();
    staged_position_ = staged_velocity_ = nullptr;
}

HaloExchange::Swap HaloExchange::on_route(const SwapRoute& route) {
    Swap swap;
    swap.send_rank = route.send_rank;
    swap.recv_rank = route.recv_rank;
    swap.to_self = route.to_self;
    swap.shift = route.shift;
    swap.turns = route.turns;
    return swap;
}

void HaloExchange::build(ParticleStore& store, const RankGrid& grid, double width,
                         unsigned fields) {
    // A refresh left in flight (a run stopped between its start and the forces, its last good
    // state restored) lands first: its receives write into the arrays rebuilt below.
    end_refresh();
    fields |= kPosition;
    comm_ = grid.comm();
    exports_elsewhere_ = false;
    store.resize_ghosts(0);
    swaps_.clear();
    const std::size_t stride = packed_bytes(store, fields);
    const Vec3 lo = grid.lo(), hi = grid.hi();
    wedge_ = grid.global().wedge;
    std::size_t n_candidates = 0;
    for (const SwapRoute& route : halo_routes(grid)) {
        // Both faces of a phase export from the particles present before it began, so a ghost
        // imported through -d is not sent straight back through +d.
        if (route.starts_phase) n_candidates = store.size();
        Swap swap = on_route(route);
        const int d = route.axis;
        for (std::size_t i = 0; i < n_candidates && swap.send_rank != MPI_PROC_NULL; ++i) {
            const double x = store.position[i][d];
            if (route.side == 0 ? x < lo[d] + width : x >= hi[d] - width)
                swap.export_index.push_back(static_cast<int>(i));
        }
        if (d < 0) wedge_exports(store, width, n_candidates, swap);
        unsigned long n_send = swap.export_index.size(), n_recv = 0;
        if (swap.to_self)
            n_recv = n_send;
        else
            send_receive(&n_send, sizeof n_send, swap.send_rank, &n_recv, sizeof n_recv,
                         swap.recv_rank, kCountTag, comm_, build_traffic_);
        send_buffer_.clear();
        pack_fields_shifted(store, fields, swap, stride);
        recv_buffer_.resize(n_recv * stride);
        if (swap.to_self && d < 0)
            recv_buffer_.assign(send_buffer_.begin(), send_buffer_.end());  // a cut face: no message
        else
            exchange(swap, send_buffer_.data(), send_buffer_.size(), recv_buffer_.data(),
                     recv_buffer_.size(), kDataTag, build_traffic_);
        swap.import_first = store.size();
        swap.import_count = n_recv;
        store.resize_ghosts(store.n_ghost() + n_recv);
        unpack_fields(store, fields, recv_buffer_.data(), n_recv, swap.import_first);
        swaps_.push_back(std::move(swap));
    }
    n_ghost_ = store.n_ghost();
}

void HaloExchange::wedge_exports(const ParticleStore& store, double width, std::size_t n_candidates,
                                 Swap& swap) const {
    // x and y are whole on this rank, so both cut faces are ours: copies from near the face
    // theta = 0 are turned by +1 wedge angle (they appear beyond the other face), copies from
    // near theta = 2 pi / n by -1.
    for (std::size_t i = 0; i < n_candidates; ++i) {
        const Vec3& x = store.position[i];
        const double gap = swap.turns == 1 ? Wedge::distance_to_first_face(x) : wedge_.distance_to_second_face(x);
        if (gap < width) swap.export_index.push_back(static_cast<int>(i));
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
    const std::vector<SwapRoute> routes = halo_routes(grid);
    if (routes.size() != plans.size())
        throw std::logic_error("HaloExchange::adopt_plan: the swaps are not the halo's routes");
    for (std::size_t k = 0; k < routes.size(); ++k) {
        const SwapRoute& route = routes[k];
        if (plans[k].to_self != route.to_self || plans[k].turns != route.turns ||
            plans[k].shift.x != route.shift.x || plans[k].shift.y != route.shift.y ||
            plans[k].shift.z != route.shift.z)
            throw std::logic_error("HaloExchange::adopt_plan: the swaps are not the halo's routes");
        Swap swap = on_route(route);
        swap.import_first = plans[k].import_first;
        swap.import_count = plans[k].import_count;
        n_ghost_ += swap.import_count;
        swaps_.push_back(std::move(swap));
    }
    exports_elsewhere_ = true;
}

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
        const double start = MPI_Wtime();
        exchange(swap, send_vectors_.data(), n * sizeof(Vec3), field.data() + swap.import_first,
                 swap.import_count * sizeof(Vec3), kDataTag, refresh_traffic_);
        if (!swap.to_self) wait_seconds_ += MPI_Wtime() - start;
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
