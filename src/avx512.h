// <immintrin.h> for the AVX-512 paths, included once the same way everywhere: GCC 12 reports its
// own intrinsics' deliberately undefined start values (_mm512_undefined_*) as (maybe)
// uninitialized where they are inlined; clang has no such warning.
#pragma once

#if defined(__AVX512F__)
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
