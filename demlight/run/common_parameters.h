// The parameter groups several commands declare alike (demlight/run/parameters.h): the DEM and
// its heights, the output raster, the horizon search, the tiles, an instant, local days, the
// sun's diameter, a canopy, a colour raster, and the clear-sky parameters.
#pragma once

#include "demlight/geo/dem.h"
#include "demlight/products/canopy.h"
#include "demlight/products/product.h"
#include "demlight/run/options.h"
#include "demlight/run/parameters.h"
#include "demlight/run/runner.h"

#include <string>

namespace demlight {

/// The DEM (the command line's positional argument and QGIS's input layer; Python passes it as
/// the call's first argument).
void declareDem(ParameterSet& set, std::string& path);
/// z_unit and z_factor: how the DEM's heights are read.
void declareHeights(ParameterSet& set, HeightOptions& heights);
/// The output raster: output (-o), format (--of), creation_options (--co). Python writes with
/// Result.write(path, format, creation_options), so these are the command line's and QGIS's.
void declareOutput(ParameterSet& set, OutputOptions& out);
/// max_distance, refraction, threads, quality, tolerance, near_field, and the command line's
/// verbose.
void declareSearch(ParameterSet& set, SearchRequest& search, bool& verbose);
/// tile_size, memory_limit, srcwin.
void declareTiling(ParameterSet& set, TilingOptions& tiling);
/// time (required) and tz.
void declareTime(ParameterSet& set, std::string& time, std::string& tz);
/// date, start, end (and with o.periods month and year), tz; `tzHelp` says what tz is the zone of.
void declareDays(ParameterSet& set, DayOptions& o, const std::string& tzHelp);
void declareSunDiameter(ParameterSet& set, double& diameterDeg);
void declareCanopy(ParameterSet& set, CanopyRequest& canopy);
/// color_raster and color_encoding; `use` says what the colours are for.
void declareColorRaster(ParameterSet& set, std::string& path, std::string& encoding, const std::string& use);
/// linke, albedo, coeff_bh, coeff_dh, their rasters, diffuse_model and solar_constant;
/// `monthOf` says whose month picks a monthly Linke value.
void declareClearSky(ParameterSet& set, ClearSkyOptions& o, const std::string& monthOf);

/// SPA's stated pressure limit (hPa; Reda & Andreas, Table 1); 0 = no atmospheric refraction.
inline constexpr double kMaxPressureHpa = 5000;

}  // namespace demlight
