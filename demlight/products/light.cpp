#include "demlight/core/parallel.h"
#include "demlight/products/light.h"

#include "demlight/lighting/aperture.h"
#include "demlight/lighting/canopy.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"
#include "demlight/products/sky.h"
#include "demlight/core/error.h"

#include <cmath>
#include <limits>

namespace demlight {
namespace {

/// The auxiliary rasters of a request, on the DEM grid.
struct LightRasters {
    Grid<float> albedo, cloud;
    std::vector<Grid<float>> color;
};

LightRasters loadRasters(const DemSource& dem, const LightRequest& r) {
    LightRasters out;
    if (!r.albedoRaster.empty())
        out.albedo = std::move(loadAuxiliaryRaster(r.albedoRaster, dem, {"albedoRaster", 1, false, 0, 1, false, {}})[0]);
    if (!r.colorRaster.empty())
        out.color = loadAuxiliaryRaster(r.colorRaster, dem, {"colorRaster", 3, true, 0, 1, true, r.colorEncoding});
    if (!r.cloudShadow.empty())
        out.cloud = std::move(loadAuxiliaryRaster(r.cloudShadow, dem, {"cloudShadow", 1, false, 0, 1, false, {}})[0]);
    return out;
}

/// The whole DEM's rasters on a window of it (the cells `dem` covers).
LightRasters rastersOnTile(const LightRasters& whole, const Dem& dem) {
    const CellWindow w = cellsOnFullGrid(dem.terrain);
    LightRasters out;
    out.albedo = cropGrid(whole.albedo, w);
    out.cloud = cropGrid(whole.cloud, w);
    for (const Grid<float>& g : whole.color) out.color.push_back(cropGrid(g, w));
    return out;
}

LightResult computeLight(const Dem& dem, const ScenePlan& plan, const LightRequest& o, const SunField& field,
                         const LightRasters& rasters, const Grid<float>& wholeCanopy, const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    const bool aperture = o.model != SunModel::Horizon;
    const bool colorRaster = !o.colorRaster.empty();
    const bool colour = colorRaster || o.sunColor || o.skyColor;
    const double albedo = o.albedo.value_or(kDefaultAlbedo);

    std::optional<CanopyTerrain> canopy;
    if (o.canopy.any()) canopy = canopyTerrain(t, wholeCanopy);
    // With a canopy the lit surface is the ground and buildings under it (demlight/lighting/canopy.h).
    const Terrain& lit = canopy ? canopy->ground : t;
    const Normals normals = computeNormals(lit);
    const bool skySweeps = o.skyModel == SkyModel::StewartLanger;
    const std::size_t directions = o.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
    const std::size_t sweeps = skySweeps || aperture ? directions : 0;
    const HorizonParams hp = integralParams(o.search, plan, t, std::max<std::size_t>(directions, 1));
    ProgressCounter counter(progress, "light",
                            t.heightsM.size() * (sweeps + (aperture ? 0 : 1)) * (canopy ? 2 : 1));

    // One pass over the directions feeds the sky and the aperture alike (without a canopy).
    std::optional<SkyAccumulator> skyAcc;
    std::optional<ApertureAccumulator> apertureAcc;
    Grid<float> canopyK;
    if (canopy && skySweeps) {
        canopyK = canopySkyK(t, *canopy, normals, directions, hp, o.canopy.transmissivity, &counter);
    } else {
        if (skySweeps)
            skyAcc.emplace(normals.east, normals.north, normals.up, directions, SkyPatches{});
        if (aperture) apertureAcc.emplace(normals.east, normals.north, normals.up, directions);
        if (sweeps > 0)
            sweepDirections(t, hp, sweeps, [&](std::size_t i, const HorizonMap& h) {
                if (skyAcc) skyAcc->addDirection(i, h.angleDeg);
                if (apertureAcc) apertureAcc->addDirection(i, h.angleDeg);
            }, &counter);
    }

    // Sun term.
    Grid<float> sunIrradiance;
    double sunDistanceM = 0;
    std::size_t sunRegions = 0;
    if (aperture) {
        ApertureLightParams lp;
        lp.sunRadiusDeg = 0.5 * o.sunDiameterDeg;
        lp.smoothIntersection = o.model == SunModel::ApertureSmooth;
        sunIrradiance = applyApertureSun(apertureAcc->finish(), normals.east, normals.north, normals.up, field, lp)
                            .irradiance;
        sunDistanceM = hp.maxDistanceM;  // the aperture is the sky's: the sky's distance
    } else {
        // auto: the distance this sun needs (sunSearchDistanceM); full: the plan's DEM diagonal.
        const SunFrameParams sp = sunFrameParams(o.search, o.sunDiameterDeg, plan);
        SunFrame frame = computeSunFrame(t, normals, field, sp, &counter);
        if (canopy)
            blendCanopySun(frame, computeSunFrame(lit, normals, field, sp, &counter), canopy->underCrown,
                           o.canopy.transmissivity);
        sunIrradiance = std::move(frame.light.irradiance);
        sunDistanceM = frame.maxDistanceM;
        sunRegions = frame.sweepRegions;
    }

    // Sky term: one grid, or one per channel when the colour raster sets the albedo.
    std::vector<Grid<float>> sky;
    for (std::size_t c = 0; c < (colorRaster ? 3 : 1); ++c) {
        const Grid<float>* albedoC = colorRaster ? &rasters.color[c] : rasters.albedo.empty() ? nullptr : &rasters.albedo;
        if (canopy && skySweeps) {
            sky.push_back(skyFactorOf(canopyK, albedoC, albedo));
        } else if (skySweeps) {
            sky.push_back((albedoC ? skyAcc->finish(*albedoC) : skyAcc->finish(albedo)).skyFactor);
        } else if (o.skyModel == SkyModel::Hemisphere) {
            HemisphereParams hemi;
            hemi.albedo = albedo;
            sky.push_back(applyHemisphereLight(normals.up, hemi, albedoC));
        }
    }

    LightTerms terms;
    terms.heightsM = &lit.heightsM;
    terms.sunIrradiance = &sunIrradiance;
    terms.cloud = rasters.cloud.empty() ? nullptr : &rasters.cloud;
    for (const auto& s : sky) terms.sky.push_back(&s);
    for (const auto& c : rasters.color) terms.reflectance.push_back(&c);
    terms.sunColor = o.sunColor.value_or(LinearRgb{1, 1, 1});
    terms.skyColor = o.skyColor.value_or(LinearRgb{1, 1, 1});
    terms.channels = colour ? 3 : 1;
    std::vector<Grid<float>> light = combineLight(terms);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, sunDistanceM, o.search.refraction));
    meta.insert({
        {"DEMLIGHT_TIME_UTC", formatInstant(o.time.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(o.time.utc, o.time.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centreAzimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centreElevationDeg)},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_SUN_SWEEP_REGIONS", aperture ? std::string() : std::to_string(sunRegions)},
        {"DEMLIGHT_MODEL", std::string(sunModelName(o.model))},
        {"DEMLIGHT_DIRECTIONS", aperture ? std::to_string(directions) : std::string()},
        {"DEMLIGHT_SKY_MODEL", std::string(skyModelName(o.skyModel))},
        {"DEMLIGHT_SKY_DIRECTIONS", std::to_string(skySweeps ? directions : 0)},
        {"DEMLIGHT_ALBEDO", colorRaster            ? std::string("per channel from the colour raster")
                            : o.albedoRaster.empty() ? formatNumber(albedo)
                                                     : o.albedoRaster},
        {"DEMLIGHT_COLOR_RASTER", o.colorRaster},
        {"DEMLIGHT_CLOUD_SHADOW", o.cloudShadow},
        {"DEMLIGHT_SKY_MAX_DISTANCE_M", sweeps > 0 ? metadataDistanceM(t, hp.maxDistanceM) : std::string()},
    });
    meta.merge(canopyMetadata(o.canopy));
    LightResult out;
    static_cast<ProductResult&>(out) = makeResult(dem, "light", meta);
    out.centreAzimuthDeg = field.centreAzimuthDeg;
    out.centreElevationDeg = field.centreElevationDeg;
    const std::string unit =
        colorRaster ? "albedo x normalised irradiance: light reflected by the ground, relative to the "
                      "source radiance (white ground under a unit zenith sun = 1)"
                    : "normalised irradiance (1 = unit zenith sun, or unit sky, on open flat ground)";
    const std::string prefix = colorRaster ? "reflected" : "light";
    if (colour) {
        const char* suffixes[3] = {"_r", "_g", "_b"};
        for (std::size_t c = 0; c < 3; ++c) out.bands.push_back({prefix + suffixes[c], unit, std::move(light[c]), {}});
    } else {
        out.bands.push_back({prefix, unit, std::move(light[0]), {}});
    }
    return out;
}

void validateLight(const LightRequest& o) {
    validateSun(o.sunDiameterDeg, o.atmosphere);
    if (!o.colorRaster.empty() && (o.albedo || !o.albedoRaster.empty()))
        throw Error("colorRaster gives the albedo of each channel; do not combine it with " +
                    std::string(o.albedo ? "albedo" : "albedoRaster"));
    if (o.albedo && !o.albedoRaster.empty()) throw Error("give albedo or albedoRaster, not both");
    if (o.albedo && !(*o.albedo >= 0 && *o.albedo <= 1))
        throw FieldError("albedo", " " + formatNumber(*o.albedo) + ": must be in [0, 1]");
    for (const auto* c : {&o.sunColor, &o.skyColor})
        if (*c)
            for (double v : **c)
                if (!(v >= 0) || !std::isfinite(v))
                    throw FieldError(c == &o.sunColor ? "sunColor" : "skyColor", ": " + formatNumber(v) +
                                " is not a linear radiance >= 0");
    if (o.skyDirections && *o.skyDirections < 1)
        throw FieldError("skyDirections", " " + std::to_string(*o.skyDirections) + ": must be >= 1");
    validateCanopy(o.canopy);
    if (o.canopy.any() && o.model != SunModel::Horizon)
        throw FieldError("canopy", ": applies to the horizon sun model only");
    if (o.canopy.any() && o.skyModel == SkyModel::Hemisphere)
        throw FieldError("canopy", ": needs a sky from horizons (the stewart-langer sky, or none), not the hemisphere");
}

}  // namespace

std::vector<Grid<float>> combineLight(const LightTerms& terms) {
    const Grid<float>& h = *terms.heightsM;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const bool reflect = terms.reflectance.size() >= terms.channels && !terms.reflectance.empty();
    std::vector<Grid<float>> light(terms.channels, Grid<float>(h.width(), h.height(), nan));
    for (std::size_t k = 0; k < h.size(); ++k) {
        if (std::isnan(h.data()[k])) continue;
        double s = terms.sunIrradiance->data()[k];
        if (terms.cloud) s *= std::isnan(terms.cloud->data()[k]) ? 1.0 : terms.cloud->data()[k];
        for (std::size_t c = 0; c < terms.channels; ++c) {
            const double skyTerm = terms.sky.empty() ? 0.0 : terms.sky[std::min(c, terms.sky.size() - 1)]->data()[k];
            const double reflectance = reflect ? terms.reflectance[c]->data()[k] : 1.0;
            light[c].data()[k] = static_cast<float>(reflectance * (terms.sunColor[c] * s + terms.skyColor[c] * skyTerm));
        }
    }
    return light;
}

namespace {

/// The halo of lightHaloCells for the plan and the sun field the product makes.
std::size_t lightHalo(const Terrain& whole, const LightRequest& request, const ScenePlan& plan, const SunField& field) {
    const double sunDistance = sunFrameDistanceM(request.search, request.sunDiameterDeg, plan, whole, field);
    const double skyDistance =
        integralParams(request.search, plan, whole,
                       request.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections)))
            .maxDistanceM;
    return haloCellsFor(whole, std::max(sunDistance, skyDistance));
}

}  // namespace

std::size_t lightHaloCells(const DemSource& source, const LightRequest& request) {
    const ScenePlan plan = planFor(request.search, source.geometry().terrain);
    return lightHalo(source.geometry().terrain, request, plan,
                     sunFieldFor(source, request.time.utc, request.atmosphere, plan));
}

LightResult lightProduct(const DemSource& source, const CellWindow& window, const LightRequest& request,
                         const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validateLight(request);
        const Dem& whole = source.geometry();
        const ScenePlan plan = planFor(request.search, whole.terrain);
        // The sun and the rasters of the whole DEM, read by each window: the same bits on its cells
        // (resampling onto a window's own georeference would round its coordinates differently).
        const SunField field = sunFieldFor(source, request.time.utc, request.atmosphere, plan);
        const LightRasters rasters = loadRasters(source, request);
        const Grid<float> canopy = loadCanopy(request.canopy, source);
        const std::size_t halo = source.isWhole(window) ? 0 : lightHalo(whole.terrain, request, plan, field);
        return onWindow<LightResult>(source, window, halo, [&](const Dem& dem) {
            if (!dem.terrain.frame) return computeLight(dem, plan, request, field, rasters, canopy, progress);  // whole DEM
            return computeLight(dem, plan, request, sunFieldOnTile(field, dem, source), rastersOnTile(rasters, dem),
                                canopy, progress);
        });
    });
}

}  // namespace demlight
