// <immintrin.h> for the AVX-512 kernels (demlight/core/simd.h: compiled with a target attribute, run where
// the processor has them), included once the same way everywhere: GCC 12 reports its own
// intrinsics' deliberately undefined start values (_mm512_undefined_*) as (maybe) uninitialized
// where they are inlined; clang has no such warning.
#pragma once

#include "demlight/core/simd.h"

#ifdef DEMLIGHT_HAS_AVX512_KERNELS
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
#include <immintrin.h>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif
