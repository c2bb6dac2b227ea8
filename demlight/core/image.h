// An 8-bit picture: what renderers make and picture writers take.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace demlight {

/// An 8-bit RGBA picture, row-major, row 0 at the top (north), 4 bytes per pixel.
struct Image8 {
    std::size_t width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
    /// Text the picture carries where its format can (PNG tEXt chunks): keyword, text.
    std::vector<std::pair<std::string, std::string>> text;
};

/// Neutral grey given to nodata pixels (alpha 0 where the format has alpha).
inline constexpr std::uint8_t kNodataGrey = 128;

}  // namespace demlight
