// SPDX-License-Identifier: MIT
// Point-to-point traffic between ranks, counted where it is sent.
#pragma once

namespace emergent {

/// Messages a rank sent to other ranks (not to itself, not to a wall's MPI_PROC_NULL) and
/// their payload in bytes, counts of what follows included.
struct MessageCounts {
    long long messages = 0;
    long long bytes = 0;
    MessageCounts& operator+=(const MessageCounts& o) {
        messages += o.messages;
        bytes += o.bytes;
        return *this;
    }
};

/// A rank's traffic by purpose: the ghosts' refresh at steps without a list build; the ghosts'
/// build at a list build (counts and copies); the migration of particles and bodies to their
/// new owners at a list build (counts and records).
struct MessageTraffic {
    MessageCounts ghost_refresh, ghost_build, migration;
};

}  // namespace emergent
