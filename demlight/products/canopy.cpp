#include "demlight/products/canopy.h"

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

std::map<std::string, std::string> canopyMetadata(const CanopyRequest& r) {
    if (!r.any()) return {};
    return {{"DEMLIGHT_CANOPY", r.raster}, {"DEMLIGHT_CANOPY_TRANSMISSIVITY", formatNumber(r.transmissivity)}};
}

}  // namespace demlight
