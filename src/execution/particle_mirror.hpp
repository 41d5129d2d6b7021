// SPDX-License-Identifier: MIT
// The particle arrays of one rank in a back end's own memory (a GPU's, or for checking, host
// memory apart from the store), with the store as their host mirror. Copies go only where the
// engine syncs (sampling, output, checkpoints, decomposition), each counted in
// exec::transfers(). The checking variant fills the host's copy of a field with a poison
// pattern once the field lives on the back end, so host code that reads it between syncs
// reads NaN (floating point) or a large negative number (integers) and fails on a CPU, not
// only on a GPU. A field lives on the back end from when it is sent (or written there) until it
// comes back; sending it again meanwhile is refused, since that would overwrite it with the
// stale host copy.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "emergent/particle_store.hpp"
#include "execution/array_memory.hpp"

namespace emergent::exec {

class ParticleMirror {
public:
    /// poison_host: the checking variant (see the file comment).
    ParticleMirror(std::unique_ptr<ArrayMemory> memory, bool poison_host);
    ~ParticleMirror();
    ParticleMirror(const ParticleMirror&) = delete;
    ParticleMirror& operator=(const ParticleMirror&) = delete;

    /// Copies `fields` of all store.size() particles to the back end (its arrays follow the
    /// store's size and fields); with poisoning, the host's copy of them is poisoned after.
    void to_backend(ParticleStore& store, unsigned fields);
    /// Copies `fields` back into the store (whose size must be the mirror's); each must hold
    /// all size() particles on the back end (sent, or written there).
    void to_host(ParticleStore& store, unsigned fields);
    /// A kernel filled `fields` for all size() particles on the back end: their host copies are
    /// stale from now on.
    void written_on_backend(unsigned fields);
    /// The fields whose current values are on the back end only (sent or written there since
    /// they last came back): sending one again would overwrite them with a stale host copy.
    unsigned resident() const { return resident_; }

    /// The back end's array of `field` (null if the store has no such field), as T*.
    template <class T>
    T* array(FieldMask field) const {
        return static_cast<T*>(find(field));
    }
    std::size_t size() const { return size_; }
    const ArrayMemory& memory() const { return *memory_; }

private:
    struct Array {
        FieldMask field;
        std::size_t element_bytes = 0, capacity = 0;
        void* data = nullptr;
        std::size_t valid = 0;  ///< leading elements holding the particles' values
    };
    void* find(FieldMask field) const;
    Array& slot(FieldMask field, std::size_t element_bytes);

    std::unique_ptr<ArrayMemory> memory_;
    bool poison_;
    std::vector<Array> arrays_;
    std::size_t size_ = 0;
    unsigned resident_ = 0;
};

}  // namespace emergent::exec
