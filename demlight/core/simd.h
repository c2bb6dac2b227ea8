// Which vector code a process runs, chosen at run time so that one build runs on any x86-64:
// the libraries are compiled for the baseline instruction set, and the kernels written for wider
// vectors carry their instruction set as a function attribute (DEMLIGHT_AVX512, DEMLIGHT_AVX2)
// and run only where simdPath() says the processor has it. Every path computes the same
// expressions (the build does not contract a multiply and an add into one rounding,
// -ffp-contract=off; the explicit fused multiply-adds are correctly rounded on every path), so
// all give the same bits; tests hold them together.
//
// The environment variable DEMLIGHT_SIMD forces a path: `portable` (the baseline code only),
// `avx2` or `avx512` (an error where the processor lacks it), `auto` or unset (the widest the
// processor has).
#pragma once

#include <atomic>
#include <optional>
#include <string_view>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
/// This compiler and target can build the AVX-512 kernels (selected at run time by simdPath()).
#define DEMLIGHT_HAS_AVX512_KERNELS 1
/// The instruction set of an AVX-512 kernel: a function attribute, on every function (lambdas
/// too) that uses AVX-512 intrinsics or vector types.
#define DEMLIGHT_AVX512 \
    __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,avx512cd,avx2,fma,bmi,bmi2,popcnt")))
/// The same for AVX2 with FMA (x86-64-v3).
#define DEMLIGHT_AVX2 __attribute__((target("avx2,fma,bmi,bmi2,popcnt")))
#else
#define DEMLIGHT_AVX2
#endif

namespace demlight {

/// In order of width: a path runs the kernels of every narrower one where it has none of its own.
enum class SimdPath {
    Portable,  // the baseline instruction set of the build
    Avx2,      // AVX2 and FMA
    Avx512,    // AVX-512 F, DQ, VL, BW and CD
};

/// "portable", "avx2" or "avx512".
std::string_view simdPathName(SimdPath path);

/// Whether this processor has the AVX-512 subsets (and AVX2, FMA) the kernels use; false where
/// the build has no such kernels.
bool processorHasAvx512();
/// Whether it has AVX2 and FMA; false where the build has no such kernels.
bool processorHasAvx2();

/// The path this process runs: DEMLIGHT_SIMD's choice, or the widest the processor has. Read once;
/// throws Error naming the variable for a value other than portable, avx2, avx512 or auto, and
/// for a path the processor lacks.
SimdPath simdPath();

/// Calls f() (a lambda marked DEMLIGHT_INLINE, whose callees are inlined too) compiled for the
/// widest instruction set simdPath() allows: for loops the compiler vectorises, and whose fused
/// multiply-adds are then instructions instead of calls to libm.
#define DEMLIGHT_INLINE __attribute__((always_inline))
#ifdef DEMLIGHT_HAS_AVX512_KERNELS
namespace detail {
template <class F>
DEMLIGHT_AVX512 void callAvx512(F& f) {
    f();
}
template <class F>
DEMLIGHT_AVX2 void callAvx2(F& f) {
    f();
}
}  // namespace detail
#endif
template <class F>
void onWidestPath(F&& f) {
#ifdef DEMLIGHT_HAS_AVX512_KERNELS
    switch (simdPath()) {
    case SimdPath::Avx512: return detail::callAvx512(f);
    case SimdPath::Avx2: return detail::callAvx2(f);
    case SimdPath::Portable: break;
    }
#endif
    f();
}

namespace detail {
/// simdPath()'s choice from DEMLIGHT_SIMD's value (null when unset) on a processor with the
/// given instruction sets.
SimdPath simdPathFor(const char* environmentValue, bool hasAvx2, bool hasAvx512);

/// For tests: forces simdPath() while it lives (nested ones restore the previous choice). Create
/// it only while no kernel runs.
class ScopedSimdPath {
public:
    explicit ScopedSimdPath(SimdPath path);
    ~ScopedSimdPath();
    ScopedSimdPath(const ScopedSimdPath&) = delete;
    ScopedSimdPath& operator=(const ScopedSimdPath&) = delete;

private:
    int previous_;
};
}  // namespace detail

}  // namespace demlight
