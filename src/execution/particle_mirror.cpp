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
    arrays_.push_back(Array{field, element_bytes, 0, nullptr});
    return arrays_.back();
}

void ParticleMirror::to_backend(ParticleStore& store, unsigned fields) {
    const std::size_t n = store.size();
    store.for_each_field([&](const FieldSpan& span) {
        Array& a = slot(span.field, span.element_bytes);
        // Every array follows the store's size, also those not copied now: their contents
        // stay the back end's (grown by 1/32 as the store grows, so ghosts do not reallocate).
        if (n > a.capacity) {
            void* grown = memory_->allocate((n + n / 32) * span.element_bytes);
            if (a.data && size_ > 0 && !(fields & span.field))
                memory_->within(grown, a.data, size_ * span.element_bytes);
            memory_->release(a.data);
            a.data = grown;
            a.capacity = n + n / 32;
        }
        if (!(fields & span.field)) return;
        const std::size_t bytes = n * span.element_bytes;
        memory_->to_backend(a.data, span.data, bytes);
        count_array(bytes);
        // 0xff bytes: a NaN in every floating-point field, -1 in every integer one.
        if (poison_) std::memset(span.data, 0xff, bytes);
    });
    size_ = n;
}

void ParticleMirror::to_host(ParticleStore& store, unsigned fields) {
    if (store.size() != size_)
        throw std::logic_error("particle mirror: the store holds " + std::to_string(store.size()) +
                               " particles, the back end " + std::to_string(size_));
    store.for_each_field([&](const FieldSpan& span) {
        if (!(fields & span.field)) return;
        const void* from = find(span.field);
        if (!from)
            throw std::logic_error("particle mirror: a field was asked back that never went to the back end");
        const std::size_t bytes = size_ * span.element_bytes;
        memory_->to_host(span.data, from, bytes);
        count_array(bytes);
    });
}

}  // namespace emergent::exec
