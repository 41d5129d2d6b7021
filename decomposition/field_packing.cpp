// SPDX-License-Identifier: MIT
// Field packing for halo exchange and migration.
#include "field_packing.hpp"

#include <cstring>

namespace emergent::decomp {

std::size_t packed_bytes(ParticleStore& store, unsigned mask) {
    std::size_t bytes = 0;
    store.for_each_field([&](const FieldSpan& f) {
        if (mask & f.field) bytes += f.element_bytes;
    });
    return bytes;
}

void pack_fields(ParticleStore& store, unsigned mask, const int* index, std::size_t n,
                 std::vector<char>& buffer) {
    const std::size_t stride = packed_bytes(store, mask);
    const std::size_t start = buffer.size();
    buffer.resize(start + n * stride);
    std::size_t offset = 0;
    // Field-major copy: one pass per field keeps the source reads sequential.
    store.for_each_field([&](const FieldSpan& f) {
        if (!(mask & f.field)) return;
        const auto* src = static_cast<const char*>(f.data);
        char* dst = buffer.data() + start + offset;
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(dst + k * stride, src + index[k] * f.element_bytes, f.element_bytes);
        offset += f.element_bytes;
    });
}

void unpack_fields(ParticleStore& store, unsigned mask, const char* buffer, std::size_t n,
                   std::size_t first) {
    const std::size_t stride = packed_bytes(store, mask);
    std::size_t offset = 0;
    store.for_each_field([&](const FieldSpan& f) {
        if (!(mask & f.field)) return;
        char* dst = static_cast<char*>(f.data) + first * f.element_bytes;
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(dst + k * f.element_bytes, buffer + k * stride + offset, f.element_bytes);
        offset += f.element_bytes;
    });
}

}  // namespace emergent::decomp
