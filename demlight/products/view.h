// An oblique view of the lit terrain for a person: a perspective picture whose ground has the
// light of the `light` product (sun visibility with the soft disk, sky K, interreflection) times
// an albedo, seen through an atmosphere (demlight/lighting/terrain_view.h), with rays cast exactly
// against the bilinear surface (demlight/lighting/max_mipmap.h). A ground pixel seen straight down with
// the atmosphere off shows albedo x the `light` value of its cell.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/terrain_view.h"
#include "demlight/products/light.h"
#include "demlight/products/product.h"
#include "demlight/products/sun.h"

#include <array>
#include <memory>
#include <optional>
#include <string>

namespace demlight {

/// A point of the camera: WGS84 latitude, longitude or x, y in the DEM's CRS, with a height in
/// metres (on the DEM's vertical datum; none: the terrain's height there).
struct ViewPoint {
    double first = 0, second = 0;
    std::optional<double> heightM;
    bool wgs84 = true;
};

/// What is drawn where the DEM has no height.
enum class ViewNodata {
    Hole,  ///< nothing: rays pass through (the sky or the ground beyond shows)
    Sea,   ///< flat water at height 0, lit by the sun and the open sky (no terrain shadows)
};

struct ViewCameraRequest {
    /// Orbit: the camera's true azimuth seen from the target (degrees; 180 = south of it, looking
    /// north), its elevation angle above the target (degrees) and its distance (metres; none =
    /// 0.75 x the DEM's diagonal). The target is the DEM centre at the terrain's height.
    double azimuthDeg = 200, elevationDeg = 25;
    std::optional<double> distanceM;
    /// Explicit eye (its height required) and target; either replaces the orbit's.
    std::optional<ViewPoint> eye, target;
    double fieldOfViewDeg = 50;  ///< horizontal
    std::size_t width = 1280, height = 720;
    double exaggeration = 1;  ///< vertical exaggeration of the terrain (and of the heights given)
};

struct ViewRequest {
    ZonedInstant time;
    ViewCameraRequest camera;
    /// Ground colour: a colour raster (the light product's colorRaster: albedo per channel), a
    /// constant grey albedo, or (neither) the default landscape albedo (landscapeAlbedo).
    std::string colorRaster;
    ColorEncoding colorEncoding = ColorEncoding::Auto;
    std::optional<double> albedo;
    /// Tree line and snow line of the default landscape (metres).
    double treeLineM = 2000, snowLineM = 3000;
    ViewNodata nodata = ViewNodata::Hole;
    ViewAtmosphere atmosphere;
    /// Linear sun and sky radiance of the light (the preview rig's by default).
    LinearRgb sunColor{1.64, 1.27, 0.99}, skyColor{0.16, 0.20, 0.28};
    double exposure = 1.0;
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    SearchRequest search;
};

/// Linear albedo of the sea (ViewNodata::Sea, and flat land at 0 m in the landscape).
inline constexpr Rgb kSeaAlbedo{0.02, 0.035, 0.05};

/// The default landscape's linear albedo of a cell from its height (metres) and the up
/// component of its normal: vegetation low and on gentle slopes, rock on slopes steeper than
/// about 40 degrees and above the tree line, snow above the snow line (metres) where it can lie
/// (slopes under about 50 degrees); smooth blends between them. Flat cells at or below 0 m are
/// sea (kSeaAlbedo), as SRTM holds it.
Rgb landscapeAlbedo(double heightM, double normalUp, double treeLineM, double snowLineM);
struct ViewResult {
    ViewImage view;
    ViewCamera camera;  ///< in the frame of demlight/lighting/terrain_view.h
    double cellWidthM = 0, cellHeightM = 0, effectiveRadiusM = 0, exaggeration = 1;
    double sunAzimuthDeg = 0, sunElevationDeg = 0;
    double eyeLatitudeDeg = 0, eyeLongitudeDeg = 0, eyeHeightM = 0, distanceToTargetM = 0;
    double lightSeconds = 0, renderSeconds = 0;
    Quality quality = Quality::Auto;
    std::size_t skyDirections = 0;
};

/// Throws Error naming the field of a bad request, and (FieldError "eye" / "camera") when the
/// camera is under the terrain.
ViewResult viewProduct(const DemSource& source, const ViewRequest& request, const ProgressFn& progress = {});

/// A view set up once (camera, surface and its pyramid, the ground's albedo) and lit for any
/// number of instants: viewProduct's picture for one, a time-lapse's frames from one camera.
class ViewStage {
public:
    /// The whole DEM of `source` (which must outlive the stage); request.time is not read. Throws
    /// as viewProduct. Pictures are rendered one at a time (render is not reentrant).
    ViewStage(const DemSource& source, const ViewRequest& request);
    ViewStage(const ViewStage&) = delete;
    ViewStage& operator=(const ViewStage&) = delete;
    ~ViewStage();

    /// The picture under per-cell light (linear R, G, B normalised irradiance before the ground's
    /// albedo, the DEM's shape) with the sun at the DEM centre at azimuth/elevation (degrees).
    ViewImage render(const std::array<const Grid<float>*, 3>& light, double sunAzimuthDeg,
                     double sunElevationDeg) const;
    /// The light of one instant from a time-lapse's terms: sunColor x sun irradiance +
    /// skyColor x f_sky(K, the sky's albedo), as `light` combines them. NaN at nodata.
    std::array<Grid<float>, 3> light(const Grid<float>& sunIrradiance, const Grid<float>& skyK) const;

    /// ViewResult's geometry fields (camera, frame, eye).
    void describe(ViewResult& out) const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace demlight
