// SPDX-License-Identifier: MIT
// Portability macros shared by host and device code.
#pragma once

#if defined(__CUDACC__)
#define EMERGENT_HD __host__ __device__
#define EMERGENT_INLINE __forceinline__
#else
#define EMERGENT_HD
#define EMERGENT_INLINE inline
#endif

#define EMERGENT_STR_DETAIL(x) #x
#define EMERGENT_STR(x) EMERGENT_STR_DETAIL(x)
/// "file:line" of the place that raised a rank-local fault.
#define EMERGENT_HERE __FILE__ ":" EMERGENT_STR(__LINE__)
