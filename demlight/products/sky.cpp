#include "demlight/core/parallel.h"
#include "demlight/products/sky.h"

#include "demlight/lighting/directions.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

namespace demlight {
namespace {

std::string albedoName(const SkyRequest& r) {
    return r.albedoRaster.empty() ? formatNumber(r.albedo) : r.albedoRaster;
}

/// sky x (1 + N_up)/2 + albedo x (1 - N_up)/2 for a unit sky (Hargreaves).
SkyResult hemisphere(const Dem& dem, const CellWindow& cells, const SkyRequest& request, const Grid<float>* albedo) {
    const Normals normals = computeNormals(dem.terrain, cells);
    HemisphereParams hp;
    hp.albedo = request.albedo;
    SkyResult out;
    static_cast<ProductResult&>(out) =
        makeResult(dem, "sky", {{"DEMLIGHT_MODEL", "hemisphere"}, {"DEMLIGHT_ALBEDO", albedoName(request)}});
    out.bands.push_back({"sky_hemisphere",
                         "normalised irradiance from a unit sky and ground of albedo C, "
                         "(1 + N_up)/2 + C (1 - N_up)/2 (Hargreaves; no terrain occlusion)",
                         applyHemisphereLight(normals.up, hp, albedo),
                         {}});
    return out;
}

/// Sky factors of `cells` of the DEM (all of it, or a tile's window inside its halo): the sweeps
/// serve those cells only, and the sums and outputs cover only them.
SkyResult stewartLanger(const Dem& dem, const CellWindow& cells, const ScenePlan& plan, const SkyRequest& request,
                        const Grid<float>* albedo, const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    const std::size_t directions = request.directions.value_or(static_cast<std::size_t>(plan.skyDirections));
    HorizonParams params = integralParams(request.search, plan, t, directions);
    params.window = sweepWindowOf(t, cells);
    const Normals normals = computeNormals(t, cells);
    SkyAccumulator sky(normals.east, normals.north, normals.up, directions, request.patches);
    ProgressCounter counter(progress, "sky", normals.up.size() * directions);
    sweepDirections(t, params, directions,
                    [&](std::size_t i, const HorizonMap& h) { sky.addDirection(i, h.angleDeg, cells); }, &counter);
    SkyMaps maps = albedo ? std::move(sky).finish(*albedo) : std::move(sky).finish(request.albedo);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, params.maxDistanceM, params.refraction));
    meta.insert({{"DEMLIGHT_METHOD", "sweep"},
                 {"DEMLIGHT_DIRECTIONS", std::to_string(directions)},
                 {"DEMLIGHT_ALBEDO", albedoName(request)},
                 {"DEMLIGHT_PATCHES", request.patches.spec}});
    SkyResult out;
    static_cast<ProductResult&>(out) = makeResult(dem, "sky", meta);
    out.directions = directions;
    out.maxDistanceM = params.maxDistanceM;
    out.directionToleranceDeg = params.directionToleranceDeg;
    out.bands = movedBands(
        ProductBand{"svf_horizontal", "fraction (cosine-weighted, horizontal plane)", std::move(maps.svfHorizontal), {}},
        ProductBand{"sky_fraction", "fraction of the upper hemisphere", std::move(maps.skyFraction), {}},
        ProductBand{"sky_K", "normalised irradiance from a unit-radiance sky", std::move(maps.skyK), {}},
        ProductBand{"sky_factor", "normalised irradiance with interreflection", std::move(maps.skyFactor), {}});
    for (std::size_t i = 0; i < maps.patchK.size(); ++i)
        out.bands.push_back({"sky_K_patch=" + request.patches.patches[i].name, "normalised irradiance",
                             std::move(maps.patchK[i]), {}});
    return out;
}

}  // namespace

std::size_t skyHaloCells(const DemSource& source, const SkyRequest& request) {
    // The hemisphere model sees no terrain: one cell for the normals.
    if (request.model == SkyModel::Hemisphere) return 1;
    const Terrain& whole = source.geometry().terrain;
    const ScenePlan plan = planFor(request.search, whole);
    return haloCellsFor(whole, integralParams(request.search, plan, whole,
                                              request.directions.value_or(static_cast<std::size_t>(plan.skyDirections)))
                                   .maxDistanceM);
}

SkyResult skyProduct(const DemSource& source, const CellWindow& window, const SkyRequest& request,
                     const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        if (request.model == SkyModel::None) throw Error("sky model 'none' makes no sky product");
        if (request.model == SkyModel::Hemisphere && !request.patches.empty())
            throw Error("patches need the stewart-langer sky model (the hemisphere model has no sky patches)");
        if (!(request.albedo >= 0 && request.albedo <= 1))
            throw FieldError("albedo", " " + formatNumber(request.albedo) + ": must be in [0, 1]");
        if (request.directions && (*request.directions < 1))
            throw FieldError("directions", " " + std::to_string(*request.directions) + ": must be >= 1");
        const Terrain& whole = source.geometry().terrain;
        const bool hemi = request.model == SkyModel::Hemisphere;
        const ScenePlan plan = planFor(request.search, whole);
        const std::size_t halo = skyHaloCells(source, request);
        // Resampled onto the whole DEM once and cut per window: the same bits on every cell.
        Grid<float> albedo;
        if (!request.albedoRaster.empty())
            albedo = std::move(loadAuxiliaryRaster(request.albedoRaster, source,
                                                   {"albedoRaster", 1, false, 0, 1, false, {}})[0]);
        return onWindowCells<SkyResult>(source, window, halo, [&](const Dem& dem, const CellWindow& cells) {
            const Terrain& t = dem.terrain;
            const CellWindow onFull{t.frameCol0 + cells.col0, t.frameRow0 + cells.row0, t.frameCol0 + cells.col1,
                                    t.frameRow0 + cells.row1};
            const Grid<float> cut = t.frame ? cropGrid(albedo, onFull) : Grid<float>();
            const Grid<float>* a = albedo.empty() ? nullptr : t.frame ? &cut : &albedo;
            return hemi ? hemisphere(dem, cells, request, a) : stewartLanger(dem, cells, plan, request, a, progress);
        });
    });
}

std::size_t skyBands(const SkyRequest& request) { return 4 + request.patches.patches.size(); }

TileBytes skyTileBytes(const SkyRequest& request) {
    // The sums become svf_horizontal, sky_fraction, sky_K and the patch bands in place
    // (SkyAccumulator::finish &&): f_sky is the one new band, and a tile's cut of an albedo raster.
    const std::size_t newBands = 1 + (request.albedoRaster.empty() ? 0 : 1);
    return windowProductTileBytes(SkyAccumulator::bytesPerCell(request.patches.size()), newBands);
}

}  // namespace demlight
