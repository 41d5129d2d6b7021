// SPDX-License-Identifier: MIT
// The particle arrays in a back end's memory; the checking host memory.
#include "execution/particle_mirror.hpp"

#include <cstdlib>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>

#include "emergent/execution.hpp"

namespace emergent::exec {

namespace {

class SeparateHostMemory final : public ArrayMemory {
public:
    void* allocate(std::size_t bytes) override {
        void* p = std::malloc(bytes > 0 ? bytes : 1);
        if (!p) throw std::bad_alloc();
        return p;
    }
    void release(void* p) noexcept override { std::free(p); }
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
}

void* ParticleMirror::find(FieldMask field) const {
    for (const auto& a : arrays_)
        if (a.field == field) return a.data;
    return nullptr;
}

ParticleMirror::Array& ParticleMirror::slot(FieldMask field, std::size_t element_bytes) {
    for (auto& a : arrays_)
        if (a.field == field) return a;
    arrays_.push_back(Array{field, element_bytes, 0, nullptr, 0});
    return arrays_.back();
}

namespace {
/// Poison for a field's host copy while the back end holds it: NaN bytes for floating-point
/// fields; for integer ones 0x80 bytes, a large negative number that is no index, id, body or
/// image count (-1 would be: it means "free particle" in the body field).
int poison_byte(FieldMask field) {
    return field == kSpecies || field == kId || field == kImage || field == kBody ? 0x80 : 0xff;
}
}  // namespace

void ParticleMirror::to_backend(ParticleStore& store, unsigned fields) {
    const std::size_t n = store.size();
    if (fields & resident_)
        throw std::logic_error("particle mirror: a field sent to the back end already lives there "
                               "(its host copy is stale): bring it back first");
    store.for_each_field([&](const FieldSpan& span) {
        Array& a = slot(span.field, span.element_bytes);
        // Every array follows the store's size, also those not copied now: their contents
        // stay the back end's (grown by 1/32 as the store grows, so ghosts do not reallocate).
        if (n > a.capacity) {
            const std::size_t capacity = n + n / 32;
            void* grown = memory_->allocate(capacity * span.element_bytes);
            try {
                if (a.data && a.valid > 0 && !(fields & span.field))
                    memory_->within(grown, a.data, a.valid * span.element_bytes);
            } catch (...) {
                memory_->release(grown);
                throw;
            }
            memory_->release(a.data);
            a.data = grown;
            a.capacity = capacity;
        }
        if (!(fields & span.field)) return;
        const std::size_t bytes = n * span.element_bytes;
        memory_->to_backend(a.data, span.data, bytes);
        count_array(bytes);
        a.valid = n;
        if (poison_) std::memset(span.data, poison_byte(span.field), bytes);
    });
    size_ = n;
    resident_ |= fields;
}

void ParticleMirror::written_on_backend(unsigned fields) {
    for (auto& a : arrays_)
        if (fields & a.field) a.valid = size_;
    resident_ |= fields;
}

void ParticleMirror::to_host(ParticleStore& store, unsigned fields) {
    if (store.size() != size_)
        throw std::logic_error("particle mirror: the store holds " + std::to_string(store.size()) +
                               " particles, the back end " + std::to_string(size_));
    store.for_each_field([&](const FieldSpan& span) {
        if (!(fields & span.field)) return;
        const Array* a = nullptr;
        for (const auto& candidate : arrays_)
            if (candidate.field == span.field) a = &candidate;
        // Only what was sent or written there comes back: a grown array holds nothing new.
        if (!a || a->valid < size_)
            throw std::logic_error("particle mirror: a field was asked back for " +
                                   std::to_string(size_) + " particles, but the back end holds " +
                                   std::to_string(a ? a->valid : 0) + " of them");
        const std::size_t bytes = size_ * span.element_bytes;
        memory_->to_host(span.data, a->data, bytes);
        count_array(bytes);
    });
    resident_ &= ~fields;
}

}  // namespace emergent::exec
