// A picture of the lit DEM for a person, with the preview rig (demlight/lighting/preview.h; after Quilez):
// sun key light with a coloured penumbra, sky fill weighted by K from exact horizon sweeps,
// bounce from opposite the sun, albedo 0.2 or a colour raster, gamma only at the end.
#pragma once

#include "demlight/geo/time.h"
#include "demlight/lighting/preview.h"
#include "demlight/products/product.h"
#include "demlight/products/sun.h"

#include <optional>
#include <string>

namespace demlight {

/// How pictures look: shared by render and time-lapse previews.
struct PictureRequest {
    /// Colour raster used as albedo (3 bands R, G, B, or one grey band); empty = `albedo`.
    std::string colorRaster;
    ColorEncoding colorEncoding = ColorEncoding::Auto;
    /// Linear albedo without a colour raster.
    double albedo = PreviewParams{}.albedo;
    /// Multiplies linear light before gamma.
    double exposure = 1.0;
    /// Ground: square ground pixels (lat/lon DEMs resampled east-west); Cell: one pixel per cell.
    PixelGeometry pixels = PixelGeometry::Ground;
};

/// Throws Error naming the field of a bad picture request.
void validatePicture(const PictureRequest& picture);
/// The colour raster of a picture request on the DEM grid (three linear albedo grids), or none.
std::vector<Grid<float>> loadPictureAlbedo(const DemSource& source, const PictureRequest& picture);

struct RenderRequest {
    ZonedInstant time;
    PictureRequest picture;
    /// Directions of the sky fill; none = the scene plan's.
    std::optional<std::size_t> skyDirections;
    double sunDiameterDeg = kSunDiameterDeg;
    SearchRequest search;
};

struct RenderResult {
    Image8 image;
    double centreAzimuthDeg = 0, centreElevationDeg = 0;
    double sunMaxDistanceM = 0;
    std::size_t skyDirections = 0;
    double skyMaxDistanceM = 0;
    Quality quality = Quality::Auto;
};

/// Renders the whole DEM (pictures are not windowed).
RenderResult renderProduct(const DemSource& source, const RenderRequest& request, const ProgressFn& progress = {});

}  // namespace demlight
