#include "demlight/lighting/canopy.h"

#include "demlight/core/error.h"

#include <cmath>

namespace demlight {

CanopyGround canopyGround(const Grid<float>& surfaceM, const Grid<float>& canopyM) {
    if (!surfaceM.sameShape(canopyM)) throw Error("canopyGround: the canopy grid is not of the surface's shape");
    CanopyGround out{surfaceM, Grid<std::uint8_t>(surfaceM.width(), surfaceM.height(), 0)};
    for (std::size_t k = 0; k < surfaceM.size(); ++k) {
        const float c = canopyM.data()[k];
        if (!(c > 0) || std::isnan(surfaceM.data()[k])) continue;
        out.groundM.data()[k] = surfaceM.data()[k] - c;
        out.underCrown.data()[k] = 1;
    }
    return out;
}

void blendCanopy(Grid<float>& surface, const Grid<float>& ground, double transmissivity) {
    if (!surface.sameShape(ground)) throw Error("blendCanopy: grids of different shapes");
    for (std::size_t k = 0; k < surface.size(); ++k)
        surface.data()[k] = static_cast<float>(transmissivity * ground.data()[k] +
                                               (1 - transmissivity) * surface.data()[k]);
}

void hideUnderCrown(Grid<float>& values, const Grid<std::uint8_t>& underCrown, float hidden) {
    if (values.width() != underCrown.width() || values.height() != underCrown.height()) throw Error("hideUnderCrown: grids of different shapes");
    for (std::size_t k = 0; k < values.size(); ++k)
        if (underCrown.data()[k] && !std::isnan(values.data()[k])) values.data()[k] = hidden;
}

void blendCanopySun(SunFrame& surface, const SunFrame& ground, const Grid<std::uint8_t>& underCrown,
                    double transmissivity) {
    // Under a crown its own crown hides the sun: O = 0 on the full surface.
    hideUnderCrown(surface.light.visibility, underCrown, 0.0f);
    hideUnderCrown(surface.light.irradiance, underCrown, 0.0f);
    blendCanopy(surface.light.visibility, ground.light.visibility, transmissivity);
    blendCanopy(surface.light.irradiance, ground.light.irradiance, transmissivity);
    surface.sweepRegions += ground.sweepRegions;
}

}  // namespace demlight
