#include "demlight/core/simd.h"

#include "demlight/core/error.h"

#include <cstdlib>
#include <string>

namespace demlight {

namespace {
// -1: not forced; otherwise the SimdPath a test forces.
std::atomic<int> forcedPath{-1};
}  // namespace

std::string_view simdPathName(SimdPath path) {
    switch (path) {
    case SimdPath::Avx512: return "avx512";
    case SimdPath::Avx2: return "avx2";
    case SimdPath::Portable: break;
    }
    return "portable";
}

bool processorHasAvx512() {
#ifdef DEMLIGHT_HAS_AVX512_KERNELS
    __builtin_cpu_init();
    return processorHasAvx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
           __builtin_cpu_supports("avx512cd");
#else
    return false;
#endif
}

bool processorHasAvx2() {
#ifdef DEMLIGHT_HAS_AVX512_KERNELS
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
           __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt");
#else
    return false;
#endif
}

SimdPath detail::simdPathFor(const char* environmentValue, bool hasAvx2, bool hasAvx512) {
    const std::string value = environmentValue ? environmentValue : "";
    if (value.empty() || value == "auto") {
        return hasAvx512 ? SimdPath::Avx512 : hasAvx2 ? SimdPath::Avx2 : SimdPath::Portable;
    }
    if (value == "portable") return SimdPath::Portable;
    if (value == "avx2" || value == "avx512") {
        if (!(value == "avx2" ? hasAvx2 : hasAvx512))
            throw Error("DEMLIGHT_SIMD=" + value + ": this processor (or this build) has no such kernels");
        return value == "avx2" ? SimdPath::Avx2 : SimdPath::Avx512;
    }
    throw Error("DEMLIGHT_SIMD=" + value + ": expected portable, avx2, avx512 or auto");
}

SimdPath simdPath() {
    const int forced = forcedPath.load(std::memory_order_relaxed);
    if (forced >= 0) return static_cast<SimdPath>(forced);
    // A function-local static: read once, and a bad value throws (again) at every call.
    static const SimdPath chosen =
        detail::simdPathFor(std::getenv("DEMLIGHT_SIMD"), processorHasAvx2(), processorHasAvx512());
    return chosen;
}

detail::ScopedSimdPath::ScopedSimdPath(SimdPath path) {
    if ((path == SimdPath::Avx512 && !processorHasAvx512()) || (path == SimdPath::Avx2 && !processorHasAvx2()))
        throw Error("ScopedSimdPath: this processor (or this build) has no " + std::string(simdPathName(path)) +
                    " kernels");
    previous_ = forcedPath.exchange(static_cast<int>(path), std::memory_order_relaxed);
}

detail::ScopedSimdPath::~ScopedSimdPath() { forcedPath.store(previous_, std::memory_order_relaxed); }

}  // namespace demlight
