// Pictures: the colour raster used as albedo, and output through OpenImageIO: single images (PNG, JPEG, EXR, ... chosen by extension)
// and animated GIFs. Files are written under a temporary name and renamed on success.
#pragma once

#include "geo/dem.h"
#include "lighting/preview.h"

#include <string>
#include <vector>

namespace demlight::cli {

/// Reads a colour raster (orthophoto, hypsometric tint) resampled onto the DEM's grid as three
/// linear albedo grids. Bands 1-3 are R, G, B (a one-band raster is grey). Values are taken as
/// display-encoded colour: 0-255 when any exceeds 1, else 0-1; decoded with gamma 2.2 to linear.
/// Throws Error naming `option` and the file on failure.
std::vector<Grid<float>> loadAlbedoRaster(const std::string& path, const Dem& dem,
                                          const std::string& option);

/// Fails early if `path`'s extension names no format OIIO can write.
void checkImagePath(const std::string& path);

/// Writes an 8-bit RGBA image; formats without alpha (JPEG) get RGB (nodata shows as the
/// neutral grey the renderer put there). Throws Error naming the path on failure.
void writeImage(const std::string& path, const Image8& image);

/// Writes frames (same size) as an animated GIF looping forever at `framesPerSecond`.
void writeAnimatedGif(const std::string& path, const std::vector<Image8>& frames,
                      int framesPerSecond);

}  // namespace demlight::cli
