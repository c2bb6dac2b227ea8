#include "demlight/run/raster_commands.h"

#include "demlight/core/error.h"
#include "demlight/products/timelapse.h"

#include <filesystem>

namespace demlight {

namespace {

/// Directions of a point query's profile when neither azimuths nor directions are given: PVGIS's
/// horizon profile, 48 values every 7.5 deg.
constexpr int kPointProfileDirections = 48;

std::string truncationPath(const std::string& outPath) {
    std::filesystem::path p(outPath);
    return (p.parent_path() / (p.stem().string() + ".truncated.tif")).string();
}

/// Bands of the sun output: sun_visibility, sun_irradiance.
constexpr std::size_t kSunBands = 2;
/// Bands of the light output (for tile sizes): light, or three of colour.
constexpr std::size_t kLightBands = 3;
/// Bands of the irradiance output: beam, diffuse, reflected, global.
constexpr std::size_t kIrradianceBands = 4;
/// Bands of the insolation output: beam, diffuse, reflected, global, sun_hours.
constexpr std::size_t kInsolationBands = 5;
/// Bands of the sunhours output: sun_hours, sun_irradiation, sky_irradiation, first_lit, last_lit.
constexpr std::size_t kSunhoursBands = 5;

/// A work's halo: the product's own declaration (xxxHaloCells) for `request`.
template <class Request>
std::function<std::size_t(const DemSource&)> haloOf(std::size_t (*halo)(const DemSource&, const Request&),
                                                   const Request& request) {
    return [halo, request](const DemSource& dem) { return halo(dem, request); };
}

}  // namespace

HorizonRequest horizonRequest(const HorizonParameters& p, bool point) {
    if (!p.azimuthsDeg.empty() && p.directions != 0) throw ParameterError("give either {azimuth} DEG [DEG ...] or {directions} N");
    if (p.azimuthsDeg.empty() && p.directions == 0 && !point)
        throw ParameterError("give either {azimuth} DEG [DEG ...] or {directions} N");
    HorizonRequest request;
    request.azimuthsDeg = p.azimuthsDeg;
    const int directions = p.azimuthsDeg.empty() && p.directions == 0 ? kPointProfileDirections : p.directions;
    for (double az : evenAzimuthsDeg(static_cast<std::size_t>(directions))) request.azimuthsDeg.push_back(az);
    request.method = parseHorizonMethod(p.method);
    request.search = p.search;
    return request;
}

ProductWork<HorizonResult> horizonWork(const HorizonRequest& request, const HorizonParameters& p) {
    ProductWork<HorizonResult> work;
    work.command = "horizon";
    work.heights = p.heights;
    work.tiling = p.tiling;
    work.threads = p.search.threads;
    work.halo = haloOf(horizonHaloCells, request);
    // Memory of a window per cell: a horizon and a mask band per azimuth.
    work.tileBytes = productTileBytes(2 * request.azimuthsDeg.size());
    work.compute = [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
        return horizonProduct(dem, w, request, progress);
    };
    work.parts = [](const HorizonResult& r) { return std::vector<const ProductResult*>{&r.horizons, &r.truncation}; };
    // The horizons in OUT, the truncation mask in OUT.truncated.tif (the same format and creation
    // options, a Byte mask either way), each naming the mask's file in its metadata.
    work.targets = [fixed = p.dataType == "Int16"](const OutputOptions& given) {
        OutputOptions out = given;
        if (fixed) out.fixedPoint = horizonFixedPoint();
        OutputOptions maskOut = out;
        maskOut.path = truncationPath(out.path);
        maskOut.fixedPoint.reset();
        return std::vector<RasterTarget>{{out, {{kTruncationMaskKey, maskOut.path}}},
                                         {maskOut, {{kTruncationMaskKey, maskOut.path}}}};
    };
    return work;
}

SunRequest sunRequest(const SunParameters& p) {
    SunRequest request;
    request.time = parseTimeOptions(p.time, p.tz);
    request.model = parseSunModel(p.model);
    request.sunDiameterDeg = p.sunDiameterDeg;
    request.atmosphere = p.atmosphere;
    request.directions = p.directions;
    request.canopy = p.canopy;
    request.search = p.search;
    return request;
}

ProductWork<SunResult> sunWork(const SunRequest& request, const SunParameters& p) {
    return singleRasterWork<SunResult>(
        "sun", p.heights, p.tiling, p.search.threads, haloOf(sunHaloCells, request), productTileBytes(kSunBands),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return sunProduct(dem, w, request, progress);
        });
}

SkyRequest skyRequest(const SkyParameters& p) {
    SkyRequest request;
    request.model = parseSkyModel(p.model);
    if (request.model == SkyModel::Hemisphere && !p.patches.empty())
        throw ParameterError("{patches} needs {model} stewart-langer (the hemisphere model has no sky patches)");
    if (!p.patches.empty()) request.patches = parseSkyPatches(p.patches);
    request.directions = p.directions;
    request.albedo = p.albedo;
    request.albedoRaster = p.albedoRaster;
    request.search = p.search;
    return request;
}

ProductWork<SkyResult> skyWork(const SkyRequest& request, const SkyParameters& p) {
    return singleRasterWork<SkyResult>(
        "sky", p.heights, p.tiling, p.search.threads, haloOf(skyHaloCells, request), skyTileBytes(request),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return skyProduct(dem, w, request, progress);
        });
}

ApertureRequest apertureRequest(const ApertureParameters& p) {
    ApertureRequest request;
    request.directions = p.directions;
    request.search = p.search;
    return request;
}

ProductWork<ApertureResult> apertureWork(const ApertureRequest& request, const ApertureParameters& p) {
    return singleRasterWork<ApertureResult>(
        "aperture", p.heights, p.tiling, p.search.threads, haloOf(apertureHaloCells, request), apertureTileBytes(),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return apertureProduct(dem, w, request, progress);
        });
}

LightRequest lightRequest(const LightParameters& p) {
    LightRequest r;
    r.time = parseTimeOptions(p.time, p.tz);
    r.model = parseSunModel(p.model);
    r.skyModel = parseSkyModel(p.skyModel);
    if (!p.sunColor.empty()) r.sunColor = parseColor(p.sunColor, "sun_color");
    if (!p.skyColor.empty()) r.skyColor = parseColor(p.skyColor, "sky_color");
    if (!p.colorRaster.empty() && (p.albedo || !p.albedoRaster.empty()))
        throw ParameterError("{color_raster} gives the albedo of each channel; do not combine it with " +
                             std::string(p.albedo ? "{albedo}" : "{albedo_raster}"));
    r.albedo = p.albedo;
    r.albedoRaster = p.albedoRaster;
    r.colorRaster = p.colorRaster;
    r.colorEncoding = parseColorEncoding(p.colorEncoding, "color_encoding");
    r.cloudShadow = p.cloudShadow;
    r.skyDirections = p.skyDirections;
    r.sunDiameterDeg = p.sunDiameterDeg;
    r.canopy = p.canopy;
    r.search = p.search;
    return r;
}

ProductWork<LightResult> lightWork(const LightRequest& request, const LightParameters& p) {
    return singleRasterWork<LightResult>(
        "light", p.heights, p.tiling, p.search.threads, haloOf(lightHaloCells, request), productTileBytes(kLightBands),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return lightProduct(dem, w, request, progress);
        });
}

IrradianceRequest irradianceRequest(const IrradianceParameters& p) {
    IrradianceRequest request;
    request.time = parseTimeOptions(p.time, p.tz);
    request.linke = parseLinkeOption(p.sky.linke);
    request.albedo = p.sky.albedo;
    request.coeffBh = p.sky.coeffBh;
    request.coeffDh = p.sky.coeffDh;
    request.rasters = clearSkyRasters(p.sky);
    request.canopy = p.canopy;
    request.diffuseModel = parseDiffuseModel(p.sky.diffuseModel);
    request.solarConstantWm2 = p.sky.solarConstantWm2;
    request.skyDirections = p.skyDirections;
    request.sunDiameterDeg = p.sunDiameterDeg;
    request.search = p.search;
    linkeFor(request);  // a bad Linke factor fails before the DEM is read
    return request;
}

ProductWork<IrradianceResult> irradianceWork(const IrradianceRequest& request, const IrradianceParameters& p) {
    return singleRasterWork<IrradianceResult>(
        "irradiance", p.heights, p.tiling, p.search.threads, haloOf(irradianceHaloCells, request), productTileBytes(kIrradianceBands),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return irradianceProduct(dem, w, request, progress);
        });
}

InsolationRequest insolationRequest(const InsolationParameters& p) {
    InsolationRequest r;
    const LocalDays days = parseDayOptions(p.days, "insolation");
    r.zone = days.zone;
    r.firstDay = days.first;
    r.lastDay = days.last;
    r.interval = days.interval;
    r.step = parseStepOption(p.step, std::chrono::minutes(1));
    r.linke = parseLinkeOption(p.sky.linke);
    r.albedo = p.sky.albedo;
    r.coeffBh = p.sky.coeffBh;
    r.coeffDh = p.sky.coeffDh;
    r.rasters = clearSkyRasters(p.sky);
    r.canopy = p.canopy;
    r.diffuseModel = parseDiffuseModel(p.sky.diffuseModel);
    r.solarConstantWm2 = p.sky.solarConstantWm2;
    r.directions = p.directions;
    r.elevationBandDeg = p.elevationBandDeg;
    r.sunDiameterDeg = p.sunDiameterDeg;
    r.search = p.search;
    return r;
}

ProductWork<InsolationResult> insolationWork(const InsolationRequest& request, const InsolationParameters& p) {
    return singleRasterWork<InsolationResult>(
        "insolation", p.heights, p.tiling, p.search.threads, haloOf(insolationHaloCells, request), productTileBytes(kInsolationBands),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return insolationProduct(dem, w, request, progress);
        });
}

SunhoursRequest sunhoursRequest(const SunhoursParameters& p) {
    SunhoursRequest r;
    const LocalDays days = parseDayOptions(p.days, "sunhours");
    r.zone = days.zone;
    r.firstDay = days.first;
    r.lastDay = days.last;
    r.step = parseStepOption(p.step, std::chrono::minutes(1));
    if (r.step < std::chrono::seconds(6) || r.step > std::chrono::hours(2))
        throw ParameterError("{step} " + p.step + ": must be from 6 s to 2 h");
    r.sunDiameterDeg = p.sunDiameterDeg;
    r.albedo = p.albedo;
    r.skyDirections = p.skyDirections;
    if (p.horizonMode != "auto") r.stackDirections = parseHorizonMode(p.horizonMode, "horizon_mode");
    r.canopy = p.canopy;
    r.search = p.search;
    return r;
}

ProductWork<SunhoursResult> sunhoursWork(const SunhoursRequest& request, const SunhoursParameters& p) {
    // Grids per cell a window holds (for tile sizes): the bands, and the stack's directions (under
    // `auto` those of a stack wherever the period may take one: the plan is not made yet).
    return singleRasterWork<SunhoursResult>(
        "sunhours", p.heights, p.tiling, p.search.threads, haloOf(sunhoursHaloCells, request),
        productTileBytes(kSunhoursBands + sunhoursStackDirectionsAtMost(request)),
        [request](const DemSource& dem, const CellWindow& w, const ProgressFn& progress) {
            return sunhoursProduct(dem, w, request, progress);
        });
}

ProductWork<HorizonResult> horizonWork(const HorizonParameters& p) {
    return horizonWork(horizonRequest(p), p);
}

ProductWork<SunResult> sunWork(const SunParameters& p) {
    return sunWork(sunRequest(p), p);
}

ProductWork<SkyResult> skyWork(const SkyParameters& p) {
    return skyWork(skyRequest(p), p);
}

ProductWork<ApertureResult> apertureWork(const ApertureParameters& p) {
    return apertureWork(apertureRequest(p), p);
}

ProductWork<LightResult> lightWork(const LightParameters& p) {
    return lightWork(lightRequest(p), p);
}

ProductWork<IrradianceResult> irradianceWork(const IrradianceParameters& p) {
    return irradianceWork(irradianceRequest(p), p);
}

ProductWork<InsolationResult> insolationWork(const InsolationParameters& p) {
    return insolationWork(insolationRequest(p), p);
}

ProductWork<SunhoursResult> sunhoursWork(const SunhoursParameters& p) {
    return sunhoursWork(sunhoursRequest(p), p);
}

}  // namespace demlight
