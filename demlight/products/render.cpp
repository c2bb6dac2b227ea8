#include "demlight/core/parallel.h"
#include "demlight/products/render.h"

#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"

#include <cmath>

namespace demlight {

/// Largest exposure accepted (a multiplier of linear light).
constexpr double kMaxExposure = 1000;

void validatePicture(const PictureRequest& p) {
    if (!(p.albedo >= 0 && p.albedo <= 1)) throw FieldError("albedo", " " + formatNumber(p.albedo) + ": must be in [0, 1]");
    if (!(p.exposure >= 0 && p.exposure <= kMaxExposure))
        throw FieldError("exposure", " " + formatNumber(p.exposure) + ": must be in [0, 1000]");
}

std::vector<Grid<float>> loadPictureAlbedo(const DemSource& source, const PictureRequest& p) {
    if (p.colorRaster.empty()) return {};
    return loadAuxiliaryRaster(p.colorRaster, source, {"colorRaster", 3, true, 0, 1, true, p.colorEncoding});
}

RenderResult renderProduct(const DemSource& source, const RenderRequest& request, const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        validatePicture(request.picture);
        validateSun(request.sunDiameterDeg, Atmosphere{});
        const std::shared_ptr<const Dem> whole = source.readWhole();
        const Dem& dem = *whole;
        const Terrain& t = dem.terrain;
        const std::vector<Grid<float>> albedo = loadPictureAlbedo(source, request.picture);
        const ScenePlan plan = planFor(request.search, t);
        const std::size_t skyDirections = request.skyDirections.value_or(static_cast<std::size_t>(plan.skyDirections));
        const HorizonParams skyParams = integralParams(request.search, plan, t, skyDirections);
        const SunField field = sunFieldFor(source, request.time.utc, Atmosphere{}, plan);
        const Normals normals = computeNormals(t);
        ProgressCounter counter(progress, "render", t.heightsM.size() * (skyDirections + 1));
        const SunFrame frame =
            computeSunFrame(t, normals, field, sunFrameParams(request.search, request.sunDiameterDeg, plan), &counter);
        const Grid<float> sky = skyLightK(t, normals, skyDirections, skyParams, &counter);
        PreviewParams pp;
        pp.albedo = request.picture.albedo;
        pp.exposure = request.picture.exposure;
        RenderResult out;
        out.image = renderPreview(normals, frame.light.visibility, sky, albedo, field.centreAzimuthDeg,
                                  field.centreElevationDeg, pp);
        if (request.picture.pixels == PixelGeometry::Ground) out.image = toGroundPixels(out.image, t);
        out.centreAzimuthDeg = field.centreAzimuthDeg;
        out.centreElevationDeg = field.centreElevationDeg;
        out.sunMaxDistanceM = frame.maxDistanceM;
        out.skyDirections = skyDirections;
        out.skyMaxDistanceM = skyParams.maxDistanceM;
        out.quality = plan.quality;
        return out;
    });
}

}  // namespace demlight
