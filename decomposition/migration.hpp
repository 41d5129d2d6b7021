// SPDX-License-Identifier: MIT
// Hands owned particles that left the local domain to the ranks that now own them.
#pragma once

#include <string>
#include <vector>

#include "emergent/message_counts.hpp"
#include "emergent/particle_store.hpp"
#include "rank_grid.hpp"

namespace emergent::decomp {

/// Why a particle could not be brought home (the words of the fault line).
inline constexpr const char* kLeftThroughClosedFace = "left the region through a closed boundary";
inline constexpr const char* kMovedMoreThanABox = "moved more than a box length between list builds";
inline constexpr const char* kMovedMoreThanADomain = "moved more than one domain between list builds";

/// The one line naming such a particle: the host's migration and the back end's list build
/// say it alike.
std::string describe_leaver(std::int64_t id, const Vec3& x, int axis, const char* why);

/// Moves owned particles to their new owners, axis by axis (x, then y, then z), so a particle
/// that crossed an edge or corner arrives in two or three hops. A particle crossing a periodic
/// boundary is wrapped back into the box and its image count updated. Ghosts are dropped.
///
/// When a particle went further than the next domain (the state is broken: the neighbour list
/// missed pairs) or left the box through a non-periodic face, every rank completes the exchange
/// and then all throw the same InstabilityError naming the first such particle.
class Migration {
public:
    void apply(ParticleStore& store, const RankGrid& grid);
    /// What this rank sent to others since it was made.
    const MessageCounts& traffic() const { return traffic_; }

private:
    void report(const ParticleStore& store, std::size_t i, int d, const char* why);
    void agree_on_faults(MPI_Comm comm);

    std::string fault_;
    std::vector<int> leaving_[2];
    std::vector<char> send_buffer_[2], recv_buffer_;
    std::vector<std::uint32_t> keep_;
    MessageCounts traffic_;
};

}  // namespace emergent::decomp
