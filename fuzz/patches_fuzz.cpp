// libFuzzer target: the --patches spec parser (parseSkyPatches in demlight/lighting/sky.h). Properties
// checked on every accepted spec: at least one patch, each a non-empty azimuth range of at most
// 360 deg and a non-empty elevation range within [-90, 90], and the patches' solid angles (on
// the whole sphere) summing to the sphere's: the patches partition it, as patch K values must
// sum to K. Rejections must be demlight::Error.
#include "demlight/lighting/sky.h"
#include "demlight/core/error.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

namespace {

[[noreturn]] void fail(const char* what, std::string_view spec) {
    std::fprintf(stderr, "patches_fuzz: %s for '%.*s'\n", what, static_cast<int>(spec.size()), spec.data());
    std::abort();
}

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
/// Relative tolerance of the partition check: float sums over up to ~10^5 patches.
constexpr double kPartitionTolerance = 1e-9;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace demlight;
    const std::string_view spec(reinterpret_cast<const char*>(data), size);
    SkyPatches p;
    try {
        p = parseSkyPatches(spec);
    } catch (const Error&) {
        return 0;
    }
    if (p.empty()) fail("no patches", spec);
    if (p.spec != spec) fail("spec not kept", spec);
    double solidAngle = 0;  // as a share of 4 pi
    for (const SkyPatch& q : p.patches) {
        const double az = q.azimuth1Deg - q.azimuth0Deg;
        if (!(az > 0 && az <= 360)) fail("azimuth range empty or over 360 deg", spec);
        if (!(q.elevation0Deg >= -90 && q.elevation0Deg < q.elevation1Deg && q.elevation1Deg <= 90))
            fail("elevation range empty or outside [-90, 90]", spec);
        if (q.name.empty()) fail("patch without a name", spec);
        solidAngle += az / 360 * (std::sin(q.elevation1Deg * kDegToRad) - std::sin(q.elevation0Deg * kDegToRad)) / 2;
    }
    if (std::abs(solidAngle - 1) > kPartitionTolerance * static_cast<double>(p.size()))
        fail("patches do not partition the sphere", spec);
    return 0;
}
