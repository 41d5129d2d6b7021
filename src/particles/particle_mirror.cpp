// SPDX-License-Identifier: MIT
// The particle arrays in a back end's memory; the checking host memory.
#include "particles/particle_mirror.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

#include "emergent/execution.hpp"

namespace emergent::exec {

namespace {

/// The checking back end's own memory. Every allocation starts poisoned (all bytes 0xFF: NaN
/// in floating point, -1 or the largest index in integers), as a device's uninitialised memory
/// may hold anything: a loop that reads what nothing wrote fails on a CPU, not only under a
/// GPU's initcheck.
class SeparateHostMemory final : public ArrayMemory {
public:
    void* allocate(std::size_t bytes) override {
        void* p = std::malloc(bytes > 0 ? bytes : 1);
        if (!p) throw std::bad_alloc();
        std::memset(p, 0xFF, bytes);
        return p;
    }
    void release(void* p) noexcept override { std::free(p); }
    void* allocate_staging(std::size_t bytes) override { return allocate(bytes); }
    void release_staging(void* p) noexcept override { release(p); }
    void to_backend(void* to, const void* from, std::size_t bytes) override { std::memcpy(to, from, bytes); }
    void to_host(void* to, const void* from, std::size_t bytes) override { std::memcpy(to, from, bytes); }
    void within(void* to, const void* from, std::size_t bytes) override { std::memcpy(to, from, bytes); }
    const char* name() const override { return "host (checking)"; }
};

void count_array(std::size_t bytes) {
    transfers().arrays += 1;
    transfers().array_bytes += bytes;
}

}  // namespace

std::unique_ptr<ArrayMemory> separate_host_memory() { return std::make_unique<SeparateHostMemory>(); }

ParticleMirror::ParticleMirror(std::unique_ptr<ArrayMemory> memory, bool poison_host)
    : memory_(std::move(memory)), poison_(poison_host) {}

ParticleMirror::~ParticleMirror() {
    for (auto& a : arrays_) memory_->release(a.data);
    for (auto* list : {&tables_, &uploads_, &scratch_})
        for (auto& b : *list) memory_->release(b.data);
    for (auto& b : staging_) memory_->release_staging(b.data);
}

ParticleMirror::Buffer& ParticleMirror::buffer(std::vector<Buffer>& list, std::size_t slot,
                                               std::size_t bytes) {
    if (slot >= list.size()) list.resize(slot + 1);
    Buffer& b = list[slot];
    if (bytes > b.capacity || !b.data) {
        const std::size_t capacity = std::max<std::size_t>(bytes + bytes / 32, 8);
        void* grown = memory_->allocate(capacity);
        memory_->release(b.data);
        b.data = grown;
        b.capacity = capacity;
        b.copied.clear();
    }
    return b;
}

const double* ParticleMirror::table(std::size_t slot, const std::vector<double>& values) {
    if (slot < tables_.size() && tables_[slot].data && tables_[slot].copied == values)
        return static_cast<const double*>(tables_[slot].data);
    const std::size_t bytes = values.size() * sizeof(double);
    Buffer& b = buffer(tables_, slot, bytes);
    memory_->to_backend(b.data, values.data(), bytes);
    count_array(bytes);
    b.copied = values;
    return static_cast<const double*>(b.data);
}

const void* ParticleMirror::upload(std::size_t slot, const void* data, std::size_t bytes) {
    Buffer& b = buffer(uploads_, slot, bytes);
    memory_->to_backend(b.data, data, bytes);
    count_array(bytes);
    return b.data;
}

void* ParticleMirror::scratch(std::size_t slot, std::size_t bytes) {
    return buffer(scratch_, slot, bytes).data;
}

void* ParticleMirror::staging(std::size_t slot, std::size_t bytes) {
    if (slot >= staging_.size()) staging_.resize(slot + 1);
    Buffer& b = staging_[slot];
    if (bytes > b.capacity || !b.data) {
        const std::size_t capacity = std::max<std::size_t>(bytes + bytes / 32, 8);
        void* grown = memory_->allocate_staging(capacity);
        memory_->release_staging(b.data);
        b.data = grown;
        b.capacity = capacity;
    }
    return b.data;
}

void ParticleMirror::copy_to_host(void* to, const void* from, std::size_t bytes) {
    memory_->to_host(to, from, bytes);
    count_array(bytes);
}

void ParticleMirror::copy_to_backend(void* to, const void* from, std::size_t bytes) {
    memory_->to_backend(to, from, bytes);
    count_array(bytes);
}

void* ParticleMirror::find(FieldMask field) const {
    for (const auto& a : arrays_)
        if (a.field == field) return a.data;
    return nullptr;
}

namespace {
/// Poison for a field's host copy while its current values are on the back end: NaN bytes for
/// floating-point fields; for integer ones 0x80 bytes, a large negative number that is no index,
/// id, body or image count (-1 would be: it means "free particle" in the body field).
int poison_byte(FieldMask field) {
    return field == kSpecies || field == kId || field == kImage || field == kBody ? 0x80 : 0xff;
}
}  // namespace

void ParticleMirror::fit(ParticleStore& store) {
    const std::size_t n = store.size();
    if (n != size_) {
        // Only host code resizes the store, and it must have had every field back first.
        if (host_stale_)
            throw std::logic_error("particle mirror: the store was resized to " + std::to_string(n) +
                                   " particles while some fields lived on the back end only");
        backend_stale_ = kAllFields;
        size_ = n;
    }
    store.for_each_field([&](const FieldSpan& span) {
        Array* a = nullptr;
        for (auto& candidate : arrays_)
            if (candidate.field == span.field) a = &candidate;
        if (!a) {
            arrays_.push_back(Array{span.field, span.element_bytes, 0, nullptr});
            a = &arrays_.back();
            backend_stale_ |= span.field;
        }
        // Contents need not move: only a stale copy can be this small.
        grow(*a, n, 0);
    });
}

void ParticleMirror::grow(Array& a, std::size_t n, std::size_t keep) {
    if (n <= a.capacity) return;
    // Grown by 1/32 beyond the need, so that ghosts varying from build to build do not
    // reallocate every time.
    const std::size_t capacity = n + n / 32;
    void* grown = memory_->allocate(capacity * a.element_bytes);
    if (keep > 0) memory_->within(grown, a.data, keep * a.element_bytes);
    memory_->release(a.data);
    a.data = grown;
    a.capacity = capacity;
}

void ParticleMirror::to_backend(ParticleStore& store, unsigned fields) {
    if ((fields & backend_stale_) && store.resize_deferred())
        throw std::logic_error("particle mirror: host values sent while the arrays' size was deferred");
    fit(store);
    store.for_each_field([&](const FieldSpan& span) {
        if (!(fields & backend_stale_ & span.field)) return;
        const std::size_t bytes = size_ * span.element_bytes;
        memory_->to_backend(find(span.field), span.data, bytes);
        count_array(bytes);
        backend_stale_ &= ~static_cast<unsigned>(span.field);
    });
}

void ParticleMirror::to_host(ParticleStore& store, unsigned fields) {
    if (!(fields & host_stale_)) return;
    if (store.resize_deferred())
        throw std::logic_error("particle mirror: the host read particles while their arrays' size was deferred");
    if (store.size() != size_)
        throw std::logic_error("particle mirror: the store holds " + std::to_string(store.size()) +
                               " particles, the back end " + std::to_string(size_));
    store.for_each_field([&](const FieldSpan& span) {
        if (!(fields & host_stale_ & span.field)) return;
        const std::size_t bytes = size_ * span.element_bytes;
        memory_->to_host(span.data, find(span.field), bytes);
        count_array(bytes);
        host_stale_ &= ~static_cast<unsigned>(span.field);
    });
}

void ParticleMirror::written_on_backend(ParticleStore& store, unsigned fields) {
    fit(store);
    store.for_each_field([&](const FieldSpan& span) {
        if (!(fields & span.field)) return;
        backend_stale_ &= ~static_cast<unsigned>(span.field);
        host_stale_ |= span.field;
    });
    poison_fields(store, fields, size_);
}

void ParticleMirror::resize_on_backend(ParticleStore& store, std::size_t n_owned, std::size_t n_ghost) {
    unsigned present = 0;
    store.for_each_field([&](const FieldSpan& span) { present |= span.field; });
    if (store.size() != size_ || (backend_stale_ & present & ~static_cast<unsigned>(kForce)))
        throw std::logic_error("particle mirror: a resize on the back end needs every field there");
    if (n_owned != store.n_owned()) store.resize_owned(n_owned);
    store.resize_ghosts(n_ghost);
    const std::size_t n = store.size();
    store.for_each_field([&](const FieldSpan& span) {
        Array* a = nullptr;
        for (auto& candidate : arrays_)
            if (candidate.field == span.field) a = &candidate;
        if (!a) throw std::logic_error("particle mirror: a field has no array on the back end");
        grow(*a, n, std::min(size_, n));
    });
    poison_fields(store, present, n);
    size_ = n;
    backend_stale_ &= ~present;
    host_stale_ |= present;
}

ParticleMirror::DeferredResize::DeferredResize(ParticleMirror& mirror, ParticleStore& store)
    : mirror_(mirror), store_(store) {
    store_.begin_deferred_resize();
}

ParticleMirror::DeferredResize::~DeferredResize() {
    store_.end_deferred_resize();
    mirror_.poison_fields(store_, mirror_.host_stale_, store_.size());
}

void ParticleMirror::poison_fields(ParticleStore& store, unsigned fields, std::size_t n) {
    // Deferred (DeferredResize): poisoned at its end, once the arrays have their size.
    if (!poison_ || store.resize_deferred()) return;
    store.for_each_field([&](const FieldSpan& span) {
        if (fields & span.field) std::memset(span.data, poison_byte(span.field), n * span.element_bytes);
    });
}

void ParticleMirror::written_on_host(unsigned fields) {
    backend_stale_ |= fields;
    host_stale_ &= ~fields;
}

}  // namespace emergent::exec
