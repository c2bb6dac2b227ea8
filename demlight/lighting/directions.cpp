#include "demlight/lighting/directions.h"

#include "demlight/core/error.h"

namespace demlight {

double directionAzimuthDeg(std::size_t index, std::size_t directions) {
    return 360.0 * static_cast<double>(index) / static_cast<double>(directions);
}

void sweepDirections(const Terrain& terrain, HorizonParams params, std::size_t directions,
                     const std::function<void(std::size_t, const HorizonMap&)>& consume,
                     ProgressCounter* progress) {
    if (directions == 0) throw Error("the number of directions must be at least 1");
    HorizonMap horizon;
    SweepBuffers buffers;
    for (std::size_t i = 0; i < directions; ++i) {
        params.azimuthDeg = directionAzimuthDeg(i, directions);
        sweepHorizonInto(terrain, params, horizon, buffers, progress);
        consume(i, horizon);
    }
}

}  // namespace demlight
