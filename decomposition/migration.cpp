// SPDX-License-Identifier: MIT
// Migration of owned particles between domains.
#include "migration.hpp"

#include <limits>
#include <sstream>

#include "emergent/error.hpp"
#include "field_packing.hpp"
#include "message_tally.hpp"
#include "reductions.hpp"

namespace emergent::decomp {

namespace {
constexpr int kCountTag = 7201;
constexpr int kDataTag = 7202;
}  // namespace

std::string describe_leaver(std::int64_t id, const Vec3& x, int axis, const char* why) {
    std::ostringstream msg;
    msg << "particle id " << id << " at (" << x.x << ", " << x.y << ", " << x.z << ") " << why << " along "
        << "xyz"[axis];
    return msg.str();
}

void Migration::report(const ParticleStore& store, std::size_t i, int d, const char* why) {
    if (fault_.empty()) fault_ = describe_leaver(store.id[i], store.position[i], d, why);
}

void Migration::agree_on_faults(MPI_Comm comm) {
    // Every rank finished the same exchanges; now all learn of the first rank's fault at once,
    // so the run stops together instead of one rank aborting the others.
    const std::string message = first_message(comm, fault_);
    fault_.clear();
    if (!message.empty()) throw InstabilityError(message);
}

void Migration::apply(ParticleStore& store, const RankGrid& grid) {
    store.resize_ghosts(0);
    const std::size_t stride = packed_bytes(store, kAllFields);
    const Vec3 lo = grid.lo(), hi = grid.hi(), len = grid.global().length();
    const Wedge& wedge = grid.global().wedge;
    if (wedge.active()) {
        // Through a cut face of the wedge and back in through the other, turned: x and y are
        // whole on every rank, so this is a local move, like a periodic wrap.
        for (std::size_t i = 0; i < store.n_owned(); ++i) {
            const int turns = wedge.turns_into(store.position[i]);
            if (!turns) continue;
            store.position[i] = wedge.rotate(store.position[i], turns);
            store.velocity[i] = wedge.rotate(store.velocity[i], turns);
        }
    }
    for (int d = 0; d < 3; ++d) {
        leaving_[0].clear();
        leaving_[1].clear();
        keep_.clear();
        const bool alone = grid.dims()[d] == 1;
        // The kept particles are listed only where some leave for another rank.
        if (!alone) keep_.reserve(store.n_owned());
        for (std::size_t i = 0; i < store.n_owned(); ++i) {
            Vec3& x = store.position[i];
            const int side = x[d] < lo[d] ? 0 : (x[d] >= hi[d] ? 1 : -1);
            if (side < 0) {
                if (!alone) keep_.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            if (grid.neighbour(d, side) == MPI_PROC_NULL) {
                report(store, i, d, kLeftThroughClosedFace);
                if (!alone) keep_.push_back(static_cast<std::uint32_t>(i));
                continue;
            }
            if (grid.wraps(d, side)) {
                x[d] += side == 0 ? len[d] : -len[d];
                store.image[i][d] += side == 0 ? -1 : 1;
            }
            leaving_[side].push_back(static_cast<int>(i));
        }
        if (alone) {
            // Our own periodic image: the wrap above was the whole move.
            for (int side = 0; side < 2; ++side)
                for (int i : leaving_[side]) {
                    if (store.position[i][d] < lo[d] || store.position[i][d] >= hi[d])
                        report(store, i, d, kMovedMoreThanABox);
                }
            continue;
        }
        for (int side = 0; side < 2; ++side) {
            send_buffer_[side].clear();
            pack_fields(store, kAllFields, leaving_[side].data(), leaving_[side].size(),
                        send_buffer_[side]);
        }
        store.permute_owned(keep_);
        store.resize_owned(keep_.size());
        for (int side = 0; side < 2; ++side) {
            unsigned long n_send = leaving_[side].size(), n_recv = 0;
            const int to = grid.neighbour(d, side), from = grid.neighbour(d, 1 - side);
            send_receive(&n_send, sizeof n_send, to, &n_recv, sizeof n_recv, from, kCountTag,
                         grid.comm(), traffic_);
            recv_buffer_.resize(n_recv * stride);
            send_receive(send_buffer_[side].data(), send_buffer_[side].size(), to, recv_buffer_.data(),
                         recv_buffer_.size(), from, kDataTag, grid.comm(), traffic_);
            const std::size_t first = store.n_owned();
            store.resize_owned(first + n_recv);
            unpack_fields(store, kAllFields, recv_buffer_.data(), n_recv, first);
            for (std::size_t i = first; i < store.n_owned(); ++i)
                if (store.position[i][d] < lo[d] || store.position[i][d] >= hi[d])
                    report(store, i, d, kMovedMoreThanADomain);
        }
    }
    agree_on_faults(grid.comm());
}

}  // namespace emergent::decomp
