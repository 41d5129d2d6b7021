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

void HaloExchange::exchange(const SwapRoute& route, const void* send, std::size_t send_bytes,
                            void* recv, std::size_t recv_bytes, int tag, MessageCounts& tally) const {
    if (route.to_self) {
        if (send_bytes) std::memcpy(recv, send, send_bytes);
        return;
    }
    send_receive(send, send_bytes, route.send_rank, recv, recv_bytes, route.recv_rank, tag, comm_, tally);
}

std::size_t HaloExchange::stage_end(std::size_t first) const {
    // Ghosts are appended swap after swap: a swap depends on the stage if it exports an index
    // at or beyond the stage's first import.
    const std::size_t imports_from = plan_.swaps.at(first).import_first;
    std::size_t k = first + 1;
    for (; k < plan_.swaps.size(); ++k) {
        const std::vector<int>& e = exports_[k];
        if (!e.empty() && static_cast<std::size_t>(*std::max_element(e.begin(), e.end())) >= imports_from) break;
    }
    return k;
}

bool HaloExchange::sends_messages(std::size_t first, std::size_t end) const {
    for (std::size_t k = first; k < end; ++k)
        if (plan_.swaps[k].route.talks()) return true;
    return false;
}

std::size_t HaloExchange::refresh_stages() const {
    std::size_t stages = 0;
    for (std::size_t k = 0, end; k < plan_.swaps.size(); k = end) {
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
    stage_send_.resize(2 * plan_.swaps.size());
    post_stage();
}

void HaloExchange::post_stage() {
    // Stages that only copy (a rank's own periodic images) or face no rank complete at once:
    // they are done here, so that every stage the caller computes across has messages.
    do {
        wait_stage();
        if (next_swap_ >= plan_.swaps.size()) return;
        post_one_stage();
    } while (!sends_messages(stage_begin_, next_swap_));
}

void HaloExchange::post_one_stage() {
    stage_begin_ = next_swap_;
    const std::size_t end = stage_end(next_swap_);
    for (std::size_t k = next_swap_; k < end; ++k) {
        const SwapRoute& route = plan_.swaps[k].route;
        const std::vector<int>& exports = exports_[k];
        const std::size_t import_first = plan_.swaps[k].import_first, import_count = plan_.swaps[k].import_count;
        for (int field = 0; field < 2; ++field) {
            std::vector<Vec3>* values = field == 0 ? staged_position_ : staged_velocity_;
            if (!values) continue;
            std::vector<Vec3>& out = stage_send_[2 * k + field];
            const std::size_t n = exports.size();
            out.resize(n);
            const GhostImage image{values->data(), exports.data(), out.data(), plan_.wedge, route.turns,
                                   field == 0 ? route.shift : Vec3{0, 0, 0}};
            for (std::size_t i = 0; i < n; ++i) image(i);
            Vec3* into = values->data() + import_first;
            if (route.to_self) {
                if (n) std::memcpy(into, out.data(), n * sizeof(Vec3));
                continue;
            }
            // A tag per swap and field: the two faces of an axis may have the same neighbour.
            const int tag = kRefreshTag + static_cast<int>(2 * k) + field;
            // Poisoned until the message lands: a ghost read too early is NaN (its pair is
            // dropped or its force is NaN), never the last step's value, so a missing wait
            // changes the result on every run (tests/mpi/halo_overlap.sh) whatever the timing.
            std::fill(into, into + import_count, Vec3{kNaN, kNaN, kNaN});
            requests_.emplace_back();
            MPI_Irecv(into, static_cast<int>(import_count * sizeof(Vec3)), MPI_BYTE, route.recv_rank, tag,
                      comm_, &requests_.back());
            requests_.emplace_back();
            MPI_Isend(out.data(), static_cast<int>(n * sizeof(Vec3)), MPI_BYTE, route.send_rank, tag, comm_,
                      &requests_.back());
            if (route.send_rank != MPI_PROC_NULL) {
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
    while (next_swap_ < plan_.swaps.size()) post_stage();
    wait_stage();
    staged_position_ = staged_velocity_ = nullptr;
}

/// The host's particles as make_halo_plan() sees them: exports chosen by position, copies
/// packed with every carried field and exchanged (the counts first), ghosts appended.
struct HaloExchange::HostPlace {
    HaloExchange& halo;
    ParticleStore& store;
    const RankGrid& grid;
    double width;
    unsigned fields;
    std::size_t stride;

    std::size_t size() const { return store.size(); }

    std::size_t select(const SwapRoute& route, std::size_t k, std::size_t n_candidates) {
        halo.exports_.resize(k + 1);
        std::vector<int>& exports = halo.exports_[k];
        if (route.axis < 0) {
            // x and y are whole on this rank, so both cut faces are ours: copies from near the
            // face theta = 0 are turned by +1 wedge angle (they appear beyond the other face),
            // copies from near theta = 2 pi / n by -1.
            const Wedge& wedge = grid.global().wedge;
            for (std::size_t i = 0; i < n_candidates; ++i) {
                const Vec3& x = store.position[i];
                const double gap = route.turns == 1 ? Wedge::distance_to_first_face(x) : wedge.distance_to_second_face(x);
                if (gap < width) exports.push_back(static_cast<int>(i));
            }
        } else if (route.send_rank != MPI_PROC_NULL) {
            const int d = route.axis;
            const double lo = grid.lo()[d] + width, hi = grid.hi()[d] - width;
            for (std::size_t i = 0; i < n_candidates; ++i) {
                const double x = store.position[i][d];
                if (route.side == 0 ? x < lo : x >= hi) exports.push_back(static_cast<int>(i));
            }
        }
        return exports.size();
    }

    std::size_t move(const SwapRoute& route, std::size_t k, std::size_t n_export) {
        unsigned long n_send = n_export, n_recv = 0;
        if (route.to_self)
            n_recv = n_send;
        else
            send_receive(&n_send, sizeof n_send, route.send_rank, &n_recv, sizeof n_recv, route.recv_rank,
                         kCountTag, halo.comm_, halo.build_traffic_);
        halo.send_buffer_.clear();
        halo.pack_fields_shifted(store, fields, route, halo.exports_.at(k), grid.global().wedge, stride);
        halo.recv_buffer_.resize(n_recv * stride);
        if (route.to_self && route.axis < 0)
            halo.recv_buffer_.assign(halo.send_buffer_.begin(), halo.send_buffer_.end());  // a cut face: no message
        else
            halo.exchange(route, halo.send_buffer_.data(), halo.send_buffer_.size(), halo.recv_buffer_.data(),
                          halo.recv_buffer_.size(), kDataTag, halo.build_traffic_);
        const std::size_t first = store.size();
        store.resize_ghosts(store.n_ghost() + n_recv);
        unpack_fields(store, fields, halo.recv_buffer_.data(), n_recv, first);
        return n_recv;
    }
};

void HaloExchange::build(ParticleStore& store, const RankGrid& grid, double width,
                         unsigned fields) {
    // A refresh left in flight (a run stopped between its start and the forces, its last good
    // state restored) lands first: its receives write into the arrays rebuilt below.
    end_refresh();
    fields |= kPosition;
    comm_ = grid.comm();
    exports_elsewhere_ = false;
    store.resize_ghosts(0);
    exports_.clear();
    HostPlace place{*this, store, grid, width, fields, packed_bytes(store, fields)};
    plan_ = make_halo_plan(grid, place);
}

void HaloExchange::pack_fields_shifted(ParticleStore& store, unsigned fields, const SwapRoute& route,
                                       const std::vector<int>& exports, const Wedge& wedge, std::size_t stride) {
    const std::size_t n = exports.size();
    pack_fields(store, fields, exports.data(), n, send_buffer_);
    // Position is the first packed field (velocity, when packed, the second); the copy lands
    // at the image across the boundary.
    const bool velocity = (fields & kVelocity) != 0;
    for (std::size_t k = 0; k < n; ++k) {
        char* record = send_buffer_.data() + k * stride;
        Vec3 x;
        std::memcpy(&x, record, sizeof(Vec3));
        if (route.turns) x = wedge.rotate(x, route.turns);
        x += route.shift;
        std::memcpy(record, &x, sizeof(Vec3));
        if (velocity && route.turns) {
            Vec3 v;
            std::memcpy(&v, record + sizeof(Vec3), sizeof(Vec3));
            v = wedge.rotate(v, route.turns);
            std::memcpy(record + sizeof(Vec3), &v, sizeof(Vec3));
        }
    }
}

void HaloExchange::adopt_plan(const RankGrid& grid, HaloPlan plan) {
    comm_ = grid.comm();
    plan_ = std::move(plan);
    exports_.clear();
    exports_elsewhere_ = true;
}

void HaloExchange::gather(std::vector<Vec3>& field, bool is_position) {
    if (exports_elsewhere_)
        throw std::logic_error("HaloExchange: this plan's export lists live on the back end");
    for (std::size_t s = 0; s < plan_.swaps.size(); ++s) {
        const HaloSwap& swap = plan_.swaps[s];
        const std::vector<int>& exports = exports_[s];
        const std::size_t n = exports.size();
        send_vectors_.resize(n);
        const Vec3 offset = is_position ? swap.route.shift : Vec3{0, 0, 0};
        const GhostImage image{field.data(), exports.data(), send_vectors_.data(), plan_.wedge, swap.route.turns,
                               offset};
        for (std::size_t k = 0; k < n; ++k) image(k);
        const double start = MPI_Wtime();
        exchange(swap.route, send_vectors_.data(), n * sizeof(Vec3), field.data() + swap.import_first,
                 swap.import_count * sizeof(Vec3), kDataTag, refresh_traffic_);
        if (!swap.route.to_self) wait_seconds_ += MPI_Wtime() - start;
    }
}

void HaloExchange::exchange_bytes(std::size_t k, const void* send, std::size_t send_bytes,
                                  void* recv, std::size_t recv_bytes) const {
    exchange(plan_.swaps.at(k).route, send, send_bytes, recv, recv_bytes, kDataTag, refresh_traffic_);
}

}  // namespace emergent::decomp
