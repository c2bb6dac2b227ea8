// Hours of direct sun, sun and sky irradiation and each cell's own first and last lit time over
// local days. Instants every `step` from local midnight of the first day to local midnight after
// the last (inclusive), integrated with the trapezoid rule (demlight/lighting/sunhours.h). The sky term
// f_sky = K / (1 - C(1 - K)) is computed once from the plan's direction sweeps and integrated
// over the cell's daylight hours (skyIrradiation).
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/quality.h"
#include "demlight/lighting/sunhours.h"
#include "demlight/products/product.h"
#include "demlight/products/sky.h"
#include "demlight/products/sun.h"

#include <chrono>
#include <optional>

namespace demlight {

/// Integration step by default: trapezoid error of sun hours about 0.3 % of a day's total on the
/// samples (docs).
inline constexpr std::chrono::minutes kDefaultSunhoursStep{10};
/// first_lit / last_lit of a valid cell the sun never reaches (hours; no clock time is negative).
inline constexpr float kNeverLitClock = -1.0f;

struct SunhoursRequest {
    std::chrono::sys_days firstDay, lastDay;  ///< local days, inclusive
    TimeZoneSpec zone;                        ///< of the days and clock times
    std::chrono::milliseconds step = kDefaultSunhoursStep;
    double sunDiameterDeg = kSunDiameterDeg;
    double albedo = kDefaultAlbedo;  ///< C of the sky term's interreflection
    /// Directions of the sky term; none = the plan's.
    std::optional<std::size_t> skyDirections;
    /// How each instant's sun horizons are found: 0 = an exact sweep along its own azimuth; N =
    /// interpolated in azimuth from N directions swept once (sunLightFromStack, the
    /// `interpolated:N` horizon mode; the stack also gives the sky term, over its N sectors);
    /// none (the default, `auto`) = sunhoursStackDirections' choice.
    std::optional<std::size_t> stackDirections;
    /// Vegetation over the DEM (a DSM) that passes a share of the beam and of the sky it hides;
    /// exact horizons only (a stack is refused with it, and `auto` takes exact).
    CanopyRequest canopy;
    SearchRequest search;
};

struct SunhoursResult : ProductResult {
    std::size_t instants = 0, instantsSwept = 0;
    std::size_t stackDirections = 0;  ///< the horizon mode that ran: 0 exact, N interpolated
};

/// The horizon mode `auto` takes the interpolated horizons (kDefaultStackDirections) for periods
/// of at least this many instants, where sweeping the stack once costs less than a sweep per
/// instant (docs/performance.md, "Sun hours: exact or interpolated").
inline constexpr std::size_t kAutoStackMinInstants = 4 * kDefaultStackDirections;

/// Instants of the request's period: every step from the first local day's start, and the last
/// day's end.
std::size_t sunhoursInstantCount(const SunhoursRequest& request);

/// The stack directions a request runs with (0 = exact): its own when given; under `auto` (none)
/// kDefaultStackDirections where the plan's quality is auto, the period has at least
/// kAutoStackMinInstants instants and the plan finds terrain (on surface models interpolating
/// across a wall's corner in azimuth errs by ten times as much) and no canopy is given; otherwise 0.
std::size_t sunhoursStackDirections(const SunhoursRequest& request, const ScenePlan& plan);

/// The same before the DEM's plan is known (for sizing tiles), from the request's quality: what
/// sunhoursStackDirections gives on terrain, so never fewer directions than it.
std::size_t sunhoursStackDirectionsAtMost(const SunhoursRequest& request);

/// Bands: sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit.
/// Cells of halo a window of `request` reads around it: its search distance in cells. The product
/// reads this halo, and a run's tiles are planned with it (demlight/run/runner.h).
std::size_t sunhoursHaloCells(const DemSource& source, const SunhoursRequest& request);

SunhoursResult sunhoursProduct(const DemSource& source, const CellWindow& window, const SunhoursRequest& request,
                               const ProgressFn& progress = {});

}  // namespace demlight
