// SPDX-License-Identifier: MIT
// The particle arrays of one rank in a back end's own memory (a GPU's, or for checking, host
// memory apart from the store), with the store as their host mirror. Each field's current
// values are on the host, on the back end, or on both; a copy goes only where a part of the step
// needs a field whose copy there is stale, and each is counted in exec::transfers(). The
// checking variant fills the host's copy of a field with a poison pattern when a kernel writes
// it on the back end, so host code that reads it before it comes back reads NaN (floating
// point) or a large negative number (integers) and fails on a CPU, not only on a GPU.
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

    /// Makes the back end hold the current values of `fields` for all store.size() particles,
    /// copying those whose back-end copy is stale. A store of another size than the back end's
    /// was resized by host code: every back-end copy is stale then, and a field whose current
    /// values were on the back end only is an error (it would be lost).
    void to_backend(ParticleStore& store, unsigned fields);
    /// Makes the store hold the current values of `fields`, copying those whose host copy is
    /// stale (the store's size must be the back end's).
    void to_host(ParticleStore& store, unsigned fields);
    /// A kernel wrote `fields` for all store.size() particles on the back end (arrays are sized
    /// to the store first): their host copies are stale, and poisoned in the checking variant.
    void written_on_backend(ParticleStore& store, unsigned fields);
    /// Host code wrote `fields` in the store (all the particles that matter): their back-end
    /// copies are stale.
    void written_on_host(unsigned fields);

    /// The store takes `n_owned` owned particles and `n_ghost` ghosts after them, on the back
    /// end: each array keeps its first min(old, new) elements there, and the host's copies of
    /// every field are stale (poisoned in the checking variant). For a list build on the back
    /// end; every field but forces (recomputed after a build) must be current on the back end.
    void resize_on_backend(ParticleStore& store, std::size_t n_owned, std::size_t n_ghost);
    /// For its lifetime, the store's host arrays are not resized by resize_on_backend (only its
    /// counts change); at its end they take the last size once, poisoned in the checking
    /// variant (ParticleStore::begin_deferred_resize: a build that drops and re-adds most
    /// particles would otherwise construct them all on the host).
    class DeferredResize {
    public:
        DeferredResize(ParticleMirror& mirror, ParticleStore& store);
        ~DeferredResize();
        DeferredResize(const DeferredResize&) = delete;
        DeferredResize& operator=(const DeferredResize&) = delete;

    private:
        ParticleMirror& mirror_;
        ParticleStore& store_;
    };
    /// Calls visit(field, element_bytes, data) for each of the back end's particle arrays.
    template <class Visitor>
    void for_each_array(Visitor&& visit) const {
        for (const auto& a : arrays_) visit(a.field, a.element_bytes, a.data);
    }
    /// A copy inside the back end's memory (not a transfer).
    void copy_within(void* to, const void* from, std::size_t bytes) { memory_->within(to, from, bytes); }

    /// Fields whose current values are on the back end only.
    unsigned backend_only() const { return host_stale_; }
    /// Fields whose back-end copy is stale (or was never made).
    unsigned host_only() const { return backend_stale_; }

    /// A small table the kernels read (per-species masses) on the back end: `values` are
    /// copied to table `slot` when they differ from what was copied there last (counted as an
    /// array), so a kernel never reads host memory.
    const double* table(std::size_t slot, const std::vector<double>& values);
    /// Copies `bytes` from host memory to buffer `slot` on the back end (counted as an array):
    /// for what the host still builds, such as the neighbour list.
    const void* upload(std::size_t slot, const void* data, std::size_t bytes);
    /// Buffer `slot` of at least `bytes` on the back end, contents undefined: scratch for
    /// kernels.
    void* scratch(std::size_t slot, std::size_t bytes);
    /// Host buffer `slot` of at least `bytes` for staging MPI messages (ArrayMemory::
    /// allocate_staging: page-locked for a CUDA device), kept and grown; contents undefined.
    void* staging(std::size_t slot, std::size_t bytes);
    /// Copies between back-end and host memory for staging (MPI), each counted as an array.
    void copy_to_host(void* to, const void* from, std::size_t bytes);
    void copy_to_backend(void* to, const void* from, std::size_t bytes);

    /// The back end's array of `field` (null if it has none yet), as T*.
    template <class T>
    T* array(FieldMask field) const {
        return static_cast<T*>(find(field));
    }
    std::size_t size() const { return size_; }
    const ArrayMemory& memory() const { return *memory_; }

private:
    /// The checking variant: the first n elements of the host's `fields` set to poison.
    void poison_fields(ParticleStore& store, unsigned fields, std::size_t n);
    struct Array {
        FieldMask field;
        std::size_t element_bytes = 0, capacity = 0;
        void* data = nullptr;
    };
    void* find(FieldMask field) const;
    /// Gives every field of the store an array of at least store.size() elements.
    void fit(ParticleStore& store);
    /// Gives `a` room for n elements, keeping its first `keep`.
    void grow(Array& a, std::size_t n, std::size_t keep);

    struct Buffer {
        void* data = nullptr;
        std::size_t capacity = 0;  ///< bytes
        std::vector<double> copied;  ///< tables: what the back end holds
    };
    /// Buffer `slot` of `list`, grown to at least `bytes` (contents not kept).
    Buffer& buffer(std::vector<Buffer>& list, std::size_t slot, std::size_t bytes);

    std::unique_ptr<ArrayMemory> memory_;
    bool poison_;
    std::vector<Array> arrays_;
    std::vector<Buffer> tables_, uploads_, scratch_, staging_;
    std::size_t size_ = 0;
    unsigned host_stale_ = 0, backend_stale_ = kAllFields;
};

}  // namespace emergent::exec
