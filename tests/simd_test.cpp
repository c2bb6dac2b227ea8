// The run-time choice of vector code (demlight/core/simd.h): DEMLIGHT_SIMD's values, and a forced path.
// That both paths give the same bits is tested where the kernels are (horizon, sky, aperture
// and every product in tests/tiling_test.cpp).
#include "demlight/core/simd.h"

#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace demlight {
namespace {

TEST(Simd, UnsetOrAutoTakesTheWidestPathTheProcessorHas) {
    for (const char* value : {static_cast<const char*>(nullptr), "", "auto"}) {
        EXPECT_EQ(detail::simdPathFor(value, true, true), SimdPath::Avx512);
        EXPECT_EQ(detail::simdPathFor(value, true, false), SimdPath::Avx2);
        EXPECT_EQ(detail::simdPathFor(value, false, false), SimdPath::Portable);
    }
}

TEST(Simd, AValueForcesItsPath) {
    EXPECT_EQ(detail::simdPathFor("portable", true, true), SimdPath::Portable);
    EXPECT_EQ(detail::simdPathFor("portable", false, false), SimdPath::Portable);
    EXPECT_EQ(detail::simdPathFor("avx2", true, true), SimdPath::Avx2);
    EXPECT_EQ(detail::simdPathFor("avx512", true, true), SimdPath::Avx512);
}

TEST(Simd, AValueItCannotHonourIsAnErrorNamingTheVariable) {
    struct Case {
        const char* value;
        bool hasAvx2, hasAvx512;
    };
    for (const Case& c : {Case{"avx512", true, false}, Case{"avx2", false, false}, Case{"AVX512", true, true},
                          Case{"sse", true, true}, Case{"portable ", true, true}}) {
        try {
            detail::simdPathFor(c.value, c.hasAvx2, c.hasAvx512);
            ADD_FAILURE() << c.value << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("DEMLIGHT_SIMD=") + c.value), std::string::npos)
                << e.what();
        }
    }
}

TEST(Simd, AScopedPathIsForcedAndRestored) {
    const SimdPath before = simdPath();
    {
        const detail::ScopedSimdPath portable(SimdPath::Portable);
        EXPECT_EQ(simdPath(), SimdPath::Portable);
        if (processorHasAvx512()) {
            const detail::ScopedSimdPath wide(SimdPath::Avx512);
            EXPECT_EQ(simdPath(), SimdPath::Avx512);
        } else {
            EXPECT_THROW(detail::ScopedSimdPath{SimdPath::Avx512}, Error);  // braces: parentheses would declare a variable
        }
        if (processorHasAvx2()) {
            const detail::ScopedSimdPath wide(SimdPath::Avx2);
            EXPECT_EQ(simdPath(), SimdPath::Avx2);
        }
        EXPECT_EQ(simdPath(), SimdPath::Portable);
    }
    EXPECT_EQ(simdPath(), before);
    EXPECT_EQ(simdPathName(SimdPath::Portable), "portable");
    EXPECT_EQ(simdPathName(SimdPath::Avx2), "avx2");
    EXPECT_EQ(simdPathName(SimdPath::Avx512), "avx512");
}

}  // namespace
}  // namespace demlight
