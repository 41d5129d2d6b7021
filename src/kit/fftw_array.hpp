// SPDX-License-Identifier: MIT
// Arrays for FFTW transforms, from fftw_malloc.
#pragma once

#include <fftw3.h>

#include <algorithm>
#include <cstddef>
#include <new>

namespace emergent {

/// n elements of T (double, or std::complex<double>, laid out as fftw_complex) aligned as
/// FFTW's SIMD kernels want. FFTW picks its kernels by the alignment of the arrays it plans
/// for; memory from the general allocator may be aligned differently on different ranks, and
/// then the same transform could round differently there, while the cell analysis must be the
/// same on every rank.
template <class T>
class FftwArray {
public:
    explicit FftwArray(std::size_t n)
        : data_(static_cast<T*>(fftw_malloc(sizeof(T) * std::max<std::size_t>(n, 1)))), n_(n) {
        if (!data_) throw std::bad_alloc();
        std::fill(data_, data_ + n_, T{});
    }
    ~FftwArray() { fftw_free(data_); }
    FftwArray(const FftwArray&) = delete;
    FftwArray& operator=(const FftwArray&) = delete;

    T* data() { return data_; }
    T& operator[](std::size_t k) { return data_[k]; }
    const T& operator[](std::size_t k) const { return data_[k]; }
    std::size_t size() const { return n_; }
    T* begin() { return data_; }
    T* end() { return data_ + n_; }

private:
    T* data_;
    std::size_t n_;
};

}  // namespace emergent
