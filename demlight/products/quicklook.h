// A quick look at one band of any raster (demlight's outputs above all): the band in a
// perceptual colour map (viridis), a colour bar with the band's unit, a title naming the product,
// the band and its time or period, nodata transparent. For a person; the values stay in the file.
#pragma once

#include "demlight/geo/raster.h"
#include "demlight/core/image.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace demlight {

/// sRGB colour (8 bits per channel) of viridis at t in [0, 1] (clamped; NaN gives t = 0).
std::array<std::uint8_t, 3> viridis(double t);

/// The values at the `low` and `high` quantiles (0-1) of the finite values of `values`, by
/// nearest rank; nullopt when none is finite.
std::optional<std::pair<double, double>> quantileRange(const Grid<float>& values, double low, double high);

/// Tick values for a colour bar over [low, high]: multiples of a step of 1, 2 or 5 x 10^k, from
/// three to about `count` + 1 of them, all within [low, high].
std::vector<double> niceTicks(double low, double high, int count);

/// The band in colour, `width` x `height` pixels: each pixel the mean of the finite values of the
/// cells its footprint covers (the nearest cell where it covers less than one), mapped through
/// viridis over [low, high] (clamped); alpha 0 and kNodataGrey where no cell is finite.
Image8 colourBand(const Grid<float>& values, double low, double high, std::size_t width, std::size_t height);

struct QuicklookRequest {
    std::string path;
    /// 1-based band number, or a band description.
    std::string band = "1";
    /// Colour range; none = the 1st and 99th percentiles of the band's values.
    std::optional<std::pair<double, double>> range;
    /// The map's longer side (pixels); the title and the colour bar are added around it.
    std::size_t mapSize = 800;
    /// Title; empty = product, band and time (or period) from the file's DEMLIGHT_* metadata.
    std::string title;
};

struct QuicklookResult {
    Image8 image;
    PictureBand band;  ///< the band read (values included)
    std::string title, unitLabel;
    double low = 0, high = 0;  ///< the colour range used
    std::size_t mapX = 0, mapY = 0, mapWidth = 0, mapHeight = 0;  ///< where the map is in the picture
};

/// The title a file's metadata gives one of its bands: "product: band, time" (or period).
std::string quicklookTitle(const PictureBand& band, const std::string& path);

/// Throws Error naming the field of a bad request, the file when it cannot be read, and when
/// the band holds no finite value.
QuicklookResult quicklookProduct(const QuicklookRequest& request);

}  // namespace demlight
