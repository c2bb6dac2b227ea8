// --at, --at-xy and --point-format of horizon, irradiance and insolation: a point query prints
// the values at one cell (demlight/products/point.h) instead of writing a raster.
#pragma once

#include "cli/common.h"
#include "demlight/products/point.h"
#include "demlight/run/parameters.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace demlight::cli {

struct PointOptions {
    std::string at, atXy;
    std::string format = "json";
};
/// Adds the options; -o (`output`) stops being required, and one of -o or a point is checked by
/// requireOutputOrPoint. `moreFormats` are --point-format choices besides json and csv, with what
/// they print, for the help text.
/// --at, --at-xy and --point-format (the command line's point queries) added to a raster
/// command's declaration, whose output is then optional; `moreFormats` are the command's own
/// point formats beside json and csv, with what each prints.
void declarePointOptions(ParameterSet& set, PointOptions& o,
                         const std::vector<std::pair<std::string, std::string>>& moreFormats = {});
/// The point of --at or --at-xy, or none.
std::optional<PointSpec> pointOf(const PointOptions& o);
/// Throws Error unless -o or a point was given.
void requireOutputOrPoint(const OutputOptions& out, const PointOptions& o);
/// Refuses options that only a raster run reads (--srcwin, --tile-size) with a point.
void refuseRasterOptions(const TilingOptions& tiling);

/// The DEM of a point query: with --max-distance only the windows the point needs are ever read
/// (DemSource::openWithoutHeightPass); without it the opening pass finds the relief that sizes
/// the default search, as for a raster.
DemSource openPointDem(const DemOptions& dem, const SearchRequest& search, const CliContext& ctx);

/// The "point" object of every point query's JSON.
nlohmann::ordered_json pointJson(const PointCell& p);
/// Prints `json` (--point-format json) or the CSV `header` and `rows` (csv) on stdout.
void printPoint(const PointOptions& o, const nlohmann::ordered_json& json, const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows);

}  // namespace demlight::cli
