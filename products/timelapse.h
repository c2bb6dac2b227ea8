// A lightmap and a preview per instant. Per frame the sun is placed per region and swept exactly
// along its own azimuth (lighting/sun_frame.h), or its horizons interpolated from a stack of
// directions swept once; the sky light K is computed once. Frames reach the caller through a
// sink as they complete, so a sequence of any length never sits in memory.
#pragma once

#include "geo/time.h"
#include "lighting/preview.h"
#include "products/product.h"
#include "products/render.h"

#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// The instants of a time-lapse and how they were chosen.
struct TimelapseInstants {
    std::vector<UtcInstant> instants;
    TimeZoneSpec zone;        ///< local times are shown in it
    std::string description;  ///< "sunrise to sunset", "start to end", ...
};

/// Every `step` from start to end (inclusive when on a step). Throws Error when end is before
/// start, the step is under a second, or there would be more than maxFrames instants.
TimelapseInstants instantsBetween(const ZonedInstant& start, const ZonedInstant& end, std::chrono::milliseconds step,
                                  std::size_t maxFrames);
/// Every `step` from sunrise to sunset at the DEM centre on the local `date` in `zone` (the
/// whole local day on polar day). Throws Error on polar night and as instantsBetween.
TimelapseInstants instantsOfDay(const Dem& dem, std::chrono::sys_days date, const TimeZoneSpec& zone,
                                std::chrono::milliseconds step, std::size_t maxFrames);

struct TimelapseRequest {
    TimelapseInstants frames;
    /// 0: a sweep per frame along its sun azimuth; N: N directions swept once, horizons
    /// interpolated in azimuth (4..720).
    std::size_t stackDirections = 0;
    /// Directions of the sky term; none = the plan's (the stack's N with stackDirections).
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    bool lightmaps = true;  ///< make each frame's sun_visibility / sun_irradiance bands
    bool previews = true;   ///< render each frame's picture
    PictureRequest picture;
    /// > 0: also fit sun_irradiance over the frames with per-cell Legendre polynomials.
    int fitDegree = 0;
    SearchRequest search;
};

struct TimelapseFrame {
    std::size_t index = 0;
    UtcInstant time;
    std::string localTime;      ///< ISO 8601 in the request's zone
    double centreAzimuthDeg = 0, centreElevationDeg = 0;
    bool sunUp = false;
    ProductResult lightmap;     ///< bands sun_visibility, sun_irradiance (when lightmaps)
    Image8 preview;             ///< when previews
};

struct TimelapseSink {
    /// The sky term every frame shares (band sky_k), before the first frame.
    std::function<void(ProductResult&&)> sky;
    /// Each frame in order, as it completes.
    std::function<void(TimelapseFrame&&)> frame;
};

struct TimelapseResult {
    std::size_t frames = 0, sunUpFrames = 0;
    std::size_t skyDirections = 0;
    double skyMaxDistanceM = 0;
    Quality quality = Quality::Auto;
    double skySeconds = 0;  ///< time spent on the sky term (and the stack)
    /// fitDegree > 0: bands sun_irradiance_legendre_<j> and rms_error.
    std::optional<ProductResult> fit;
    double fitMeanRms = 0, fitWorstRms = 0;
};

/// "exact" -> 0; "interpolated" -> 64; "interpolated:N" -> N (4..720). Throws naming `field`.
std::size_t parseHorizonMode(const std::string& text, const std::string& field);

/// Runs the whole DEM (time-lapses are not windowed yet), frame by frame into the sink.
TimelapseResult timelapseProduct(const DemSource& source, const TimelapseRequest& request, const TimelapseSink& sink,
                                 const ProgressFn& progress = {});

}  // namespace demlight
