// A lightmap and a preview per instant. Per frame the sun is placed per region and swept exactly
// along its own azimuth (demlight/lighting/sun_frame.h), or its horizons interpolated from a stack of
// directions swept once; the sky light K is computed once. Frames reach the caller through a
// sink as they complete, so a sequence of any length never sits in memory. Like every raster
// product it computes any window of the DEM with its halo and gives it the whole DEM's bits, so
// a tiled run holds one tile (plus halo) and its sky term, and streams each frame's tile.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/preview.h"
#include "demlight/products/canopy.h"
#include "demlight/products/product.h"
#include "demlight/products/render.h"
#include "demlight/products/view.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
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
    /// Previews in an oblique view from this camera (demlight/products/view.h; its time is not read)
    /// instead of top-down: the frame's sun term and the sky term once, lit as `view` lights them.
    std::optional<ViewRequest> view;
    /// > 0: also fit sun_irradiance over the frames with per-cell Legendre polynomials.
    int fitDegree = 0;
    /// Vegetation that passes a share of the light (demlight/lighting/canopy.h): every frame's sun
    /// and the sky term blended from the ground-and-buildings surface and the full one. Exact
    /// horizons only (stackDirections 0).
    CanopyRequest canopy;
    SearchRequest search;
};

struct TimelapseFrame {
    std::size_t index = 0;
    UtcInstant time;
    std::string localTime;      ///< ISO 8601 in the request's zone
    double centreAzimuthDeg = 0, centreElevationDeg = 0;
    bool sunUp = false;
    ProductResult lightmap;     ///< bands sun_visibility, sun_irradiance (when lightmaps), on the window
    Image8 preview;             ///< when previews
    /// The preview's pixels are the previous frame's, bit for bit (a night picture drawn once
    /// while the frames stay dark): a writer may reuse what it made of them (its text differs).
    bool previewRepeats = false;
};

/// The sequence fit's RMS residuals over the valid cells of a run, merged across its windows.
/// The mean is summed exactly (the floats' mantissas per exponent, in integers), so the windows
/// of a tiled run give the one-piece mean to the bit whatever their order.
struct FitStats {
    std::size_t cells = 0;
    double worstRms = 0;
    std::array<std::uint64_t, 256> rmsMantissas{};  ///< indexed by the float's biased exponent

    /// One cell's RMS residual (finite, >= 0).
    void add(float rms);
    void merge(const FitStats& other);
    double meanRms() const;
    /// The fit raster's metadata items that depend on every cell of the run.
    std::map<std::string, std::string> metadata() const;
};

struct TimelapseSink {
    /// The sky term every frame shares (band sky_k), before the first frame.
    std::function<void(ProductResult&&)> sky;
    /// Each frame in order, as it completes.
    std::function<void(TimelapseFrame&&)> frame;
};

struct TimelapseResult {
    std::size_t frames = 0;
    std::size_t skyDirections = 0;
    double skyMaxDistanceM = 0;
    Quality quality = Quality::Auto;
    double skySeconds = 0;  ///< time spent on the sky term (and the stack)
    /// fitDegree > 0: bands sun_irradiance_legendre_<j> and rms_error, on the window.
    std::optional<ProductResult> fit;
    FitStats fitStats;  ///< of the window's cells
    /// Per frame: whether the sun is up over the window (a sweep region of it has the sun above
    /// the horizon; with a stack, the sun is up somewhere on the DEM).
    std::vector<bool> sunUp;
};

/// "exact" -> 0; "interpolated" -> 64; "interpolated:N" -> N (4..720). Throws naming `field`.
std::size_t parseHorizonMode(const std::string& text, const std::string& field);

/// Runs `window` of the DEM (the whole DEM, a tile or a --srcwin window, computed with its halo:
/// the sky term's search and the longest any frame's sun needs), frame by frame into the sink;
/// the sky term, each lightmap and the fit cover the window. Previews are pictures of the whole
/// DEM: request.previews on any other window throws FieldError("previews").
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t timelapseHaloCells(const DemSource& source, const TimelapseRequest& request);

TimelapseResult timelapseProduct(const DemSource& source, const CellWindow& window, const TimelapseRequest& request,
                                 const TimelapseSink& sink, const ProgressFn& progress = {});

/// Float32 grids a run holds per cell besides what every horizon product holds
/// (productBytesPerCell): the sky term, a frame's two bands, the stack's directions and the
/// fit's accumulators. For sizing tiles.
std::size_t timelapseGridsPerCell(const TimelapseRequest& request);

}  // namespace demlight
