// SPDX-License-Identifier: MIT
// A store of particles (or of rigid bodies) where the step's loops find it: the store itself on
// the host back end, or its mirror in a back end's own memory. Each part of the step says what
// it reads and writes where it runs; the mirror copies a field only where its copy there is
// stale. On the host back end all of this is nothing.
#pragma once
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "emergent/particle_store.hpp"
#include "particles/particle_mirror.hpp"

namespace emergent {

class Resident {
public:
    explicit Resident(ParticleStore& store) : store_(&store) {}

    /// From now on the arrays live in `mirror` too (a back end with its own memory).
    void keep_mirror(std::unique_ptr<exec::ParticleMirror> mirror) { mirror_ = std::move(mirror); }
    exec::ParticleMirror* mirror() const { return mirror_.get(); }
    bool mirrored() const { return mirror_ != nullptr; }

    /// The host's copy. Bringing it up to date is no change of the simulation's state, so const
    /// holders may sync it.
    ParticleStore& store() const { return *store_; }

    /// A loop on the back end reads `fields` / wrote them.
    void backend_reads(unsigned fields) const {
        if (mirror_) mirror_->to_backend(*store_, fields);
    }
    void backend_wrote(unsigned fields) const {
        if (mirror_) mirror_->written_on_backend(*store_, fields);
    }
    /// Host code reads `fields` / wrote them in the store.
    void host_reads(unsigned fields) const {
        if (mirror_) mirror_->to_host(*store_, fields);
    }
    void host_wrote(unsigned fields) const {
        if (mirror_) mirror_->written_on_host(fields);
    }

    /// The array of `field` the back end's loops work on (`host` is the store's own).
    template <class T>
    T* data(FieldMask field, const std::vector<T>& host) const {
        return mirror_ ? mirror_->array<T>(field) : const_cast<T*>(host.data());
    }
    /// A small table (per-species values) where the back end's loops read it.
    const double* table(std::size_t slot, const std::vector<double>& values) const {
        return mirror_ ? mirror_->table(slot, values) : values.data();
    }

private:
    ParticleStore* store_;
    std::unique_ptr<exec::ParticleMirror> mirror_;
};

}  // namespace emergent
