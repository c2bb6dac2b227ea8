#include "demlight/core/parallel.h"
#include "demlight/products/aperture.h"

#include "demlight/lighting/aperture.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

namespace demlight {

std::size_t apertureHaloCells(const DemSource& source, const ApertureRequest& request) {
    const Terrain& whole = source.geometry().terrain;
    const ScenePlan plan = planFor(request.search, whole);
    const std::size_t directions = request.directions.value_or(static_cast<std::size_t>(plan.skyDirections));
    return haloCellsFor(whole, integralParams(request.search, plan, whole, directions).maxDistanceM);
}

ApertureResult apertureProduct(const DemSource& source, const CellWindow& window, const ApertureRequest& request,
                               const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        if (request.directions && *request.directions < 1)
            throw FieldError("directions", " " + std::to_string(*request.directions) + ": must be >= 1");
        const Terrain& whole = source.geometry().terrain;
        const ScenePlan plan = planFor(request.search, whole);
        const std::size_t directions = request.directions.value_or(static_cast<std::size_t>(plan.skyDirections));
        const std::size_t halo = apertureHaloCells(source, request);
        // The sweeps serve the window's cells only; the halo is read for its occluders.
        return onWindowCells<ApertureResult>(source, window, halo, [&](const Dem& dem, const CellWindow& cells) {
            const Terrain& t = dem.terrain;
            HorizonParams params = integralParams(request.search, plan, t, directions);
            params.window = sweepWindowOf(t, cells);
            const Normals normals = computeNormals(t, cells);
            ApertureAccumulator acc(normals.east, normals.north, normals.up, directions);
            ProgressCounter counter(progress, "aperture", normals.up.size() * directions);
            sweepDirections(t, params, directions,
                            [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg, cells); },
                            &counter);
            ApertureMaps maps = acc.finish();

            std::map<std::string, std::string> meta = planMetadata(plan);
            meta.merge(searchMetadata(t, params.maxDistanceM, params.refraction));
            meta.insert({{"DEMLIGHT_METHOD", "sweep"}, {"DEMLIGHT_DIRECTIONS", std::to_string(directions)}});
            ApertureResult out;
            static_cast<ProductResult&>(out) = makeResult(dem, "aperture", meta);
            out.directions = directions;
            out.maxDistanceM = params.maxDistanceM;
            out.bands = movedBands(ProductBand{"bent_normal_east", "unit vector component (ENU)", std::move(maps.bentEast), {}},
                         ProductBand{"bent_normal_north", "unit vector component (ENU)", std::move(maps.bentNorth), {}},
                         ProductBand{"bent_normal_up", "unit vector component (ENU)", std::move(maps.bentUp), {}},
                         ProductBand{"aperture_radius_deg", "deg", std::move(maps.radiusDeg), {}},
                         ProductBand{"visible_solid_angle_sr", "sr", std::move(maps.solidAngleSr), {}});
            return out;
        });
    });
}

TileBytes apertureTileBytes() { return windowProductTileBytes(ApertureAccumulator::kBytesPerCell, kApertureBands); }

}  // namespace demlight
