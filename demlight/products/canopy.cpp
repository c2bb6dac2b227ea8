#include "demlight/products/canopy.h"

#include "demlight/lighting/canopy.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/sky.h"
#include "demlight/products/product.h"
#include "demlight/core/error.h"

namespace demlight {

void validateCanopy(const CanopyRequest& r) {
    if (!(r.transmissivity >= 0 && r.transmissivity <= 1))
        throw FieldError("transmissivity", " " + formatNumber(r.transmissivity) + ": must be in [0, 1]");
}

Grid<float> loadCanopy(const CanopyRequest& r, const DemSource& source) {
    if (!r.any()) return {};
    return std::move(loadAuxiliaryRaster(r.raster, source, {"canopyRaster", 1, false, 0, kMaxCanopyHeightM, false, {}})[0]);
}

CanopyTerrain canopyTerrain(const Terrain& surface, const Grid<float>& wholeCanopy) {
    const Grid<float> canopy = surface.frame ? cropGrid(wholeCanopy, cellsOnFullGrid(surface)) : wholeCanopy;
    CanopyGround g = canopyGround(surface.heightsM, canopy);
    CanopyTerrain out{surface, std::move(g.underCrown)};
    out.ground.heightsM = std::move(g.groundM);
    return out;
}

Grid<float> canopySkyK(const Terrain& surface, const CanopyTerrain& canopy, const Normals& normals,
                       std::size_t directions, const HorizonParams& params, double transmissivity,
                       ProgressCounter* progress) {
    SkyAccumulator full(normals.east, normals.north, normals.up, directions, SkyPatches{});
    Grid<float> hidden;
    sweepDirections(surface, params, directions, [&](std::size_t i, const HorizonMap& h) {
        hidden = h.angleDeg;
        hideUnderCrown(hidden, canopy.underCrown, 90.0f);
        full.addDirection(i, hidden);
    }, progress);
    Grid<float> k = std::move(full).finish(0.0).skyK;
    blendCanopy(k, skyLightK(canopy.ground, normals, directions, params, progress), transmissivity);
    return k;
}

std::map<std::string, std::string> canopyMetadata(const CanopyRequest& r) {
    if (!r.any()) return {};
    return {{"DEMLIGHT_CANOPY", r.raster}, {"DEMLIGHT_CANOPY_TRANSMISSIVITY", formatNumber(r.transmissivity)}};
}

}  // namespace demlight
