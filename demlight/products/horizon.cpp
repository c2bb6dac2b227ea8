#include "demlight/core/parallel.h"
#include "demlight/products/horizon.h"

#include "demlight/core/angles.h"
#include "demlight/core/error.h"

#include <cmath>

namespace demlight {

HorizonMethod parseHorizonMethod(const std::string& name) {
    if (name == "sweep") return HorizonMethod::Sweep;
    if (name == "reference") return HorizonMethod::Reference;
    throw Error("horizon method '" + name + "': expected sweep or reference");
}

const char* horizonMethodName(HorizonMethod method) {
    return method == HorizonMethod::Reference ? "reference" : "sweep";
}

std::vector<double> evenAzimuthsDeg(std::size_t directions) {
    std::vector<double> out;
    for (std::size_t i = 0; i < directions; ++i)
        out.push_back(360.0 * static_cast<double>(i) / static_cast<double>(directions));
    return out;
}

std::size_t horizonHaloCells(const DemSource& source, const HorizonRequest& request) {
    const ScenePlan plan = planFor(request.search, source.geometry().terrain);
    return haloCellsFor(source.geometry().terrain, horizonParams(request.search, plan).maxDistanceM);
}

namespace {

HorizonResult computeHorizons(const Dem& dem, const ScenePlan& plan, const HorizonRequest& request,
                              const ProgressFn& progress) {
    const Terrain& t = dem.terrain;
    HorizonParams params = horizonParams(request.search, plan);
    const bool reference = request.method == HorizonMethod::Reference;
    ProgressCounter counter(progress, reference ? "horizon (reference)" : "horizon (sweep)",
                            request.azimuthsDeg.size() * t.heightsM.size());
    std::string azimuthList;
    for (double az : request.azimuthsDeg) {
        if (!azimuthList.empty()) azimuthList.push_back(',');
        azimuthList.append(formatNumber(wrapAzimuthDeg(az)));
    }

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.merge(searchMetadata(t, params.maxDistanceM, params.refraction));
    meta.insert({{"DEMLIGHT_METHOD", horizonMethodName(request.method)}, {"DEMLIGHT_AZIMUTHS_DEG", azimuthList}});
    HorizonResult out{makeResult(dem, "horizon", meta), makeResult(dem, "horizon", meta), params.maxDistanceM};
    out.truncation.flagNodata = kTruncationMaskNodata;
    // Shared by the directions' sweeps: scratch planes, and the bitmap of valid cells.
    SweepBuffers buffers;
    for (double az : request.azimuthsDeg) {
        params.azimuthDeg = az;
        HorizonMap map;
        if (reference) {
            map = referenceHorizon(t, params, &counter);
        } else {
            sweepHorizonInto(t, params, map, buffers, &counter);
        }
        // The mask says nothing at DEM voids.
        const float* h = t.heightsM.data();
        std::uint8_t* flag = map.truncated.data();
        for (std::size_t k = 0; k < map.truncated.size(); ++k)
            if (std::isnan(h[k])) flag[k] = kTruncationMaskNodata;
        const std::string name = formatNumber(wrapAzimuthDeg(az));
        // Nearest: a horizon angle band holds kNoHorizonDeg (-90, no terrain in range) beside real
        // angles, and a mean of the two (-41) is a horizon no cell has; the mask is flags.
        out.horizons.bands.push_back({"horizon_azimuth=" + name, "deg", std::move(map.angleDeg), {}, Resampling::Nearest});
        out.truncation.bands.push_back(
            {"truncated_azimuth=" + name, "", {}, std::move(map.truncated), Resampling::Nearest});
    }
    return out;
}

}  // namespace

HorizonResult horizonProduct(const DemSource& source, const CellWindow& window, const HorizonRequest& request,
                             const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        if (request.azimuthsDeg.empty()) throw FieldError("azimuthsDeg", ": give at least one azimuth");
        for (double az : request.azimuthsDeg)
            if (!std::isfinite(az)) throw FieldError("azimuthsDeg", ": " + formatNumber(az) + " is not a finite number");
        const ScenePlan plan = planFor(request.search, source.geometry().terrain);
        const std::size_t halo = horizonHaloCells(source, request);
        return onWindow<HorizonResult>(source, window, halo,
                                       [&](const Dem& dem) { return computeHorizons(dem, plan, request, progress); });
    });
}

void cropResult(HorizonResult& result, const CellWindow& read, const CellWindow& window) {
    cropResult(result.horizons, read, window);
    cropResult(result.truncation, read, window);
}

}  // namespace demlight
