#include "cli/point_options.h"

#include "cli/common.h"
#include "cli/progress_bar.h"
#include "demlight/core/error.h"

#include <cmath>
#include <iostream>

namespace demlight::cli {
namespace {

/// "A,B" as two finite numbers; throws Error naming the option.
std::pair<double, double> parsePair(const std::string& text, const std::string& option, const std::string& form) {
    const std::size_t comma = text.find(',');
    const auto number = [&](const std::string& part) {
        const std::optional<double> v = parseFiniteNumber(part);
        if (!v) throw Error(option + " '" + text + "': expected " + form + ", two numbers separated by a comma");
        return *v;
    };
    if (comma == std::string::npos) throw Error(option + " '" + text + "': expected " + form);
    return {number(text.substr(0, comma)), number(text.substr(comma + 1))};
}

}  // namespace

void addPointOptions(CLI::App* cmd, PointOptions& o, CLI::Option* output,
                     const std::vector<std::pair<std::string, std::string>>& moreFormats) {
    output->required(false);
    auto* at = cmd->add_option("--at", o.at,
                               "Point query: print the values at WGS84 LAT,LON (degrees; --at=-33.9,18.4 when the "
                               "first is negative) instead of writing a raster")
                   ->type_name("LAT,LON");
    auto* xy = cmd->add_option("--at-xy", o.atXy, "Point query at X,Y in the DEM's CRS (as --at)")->type_name("X,Y");
    at->excludes(xy);
    at->excludes(output);
    xy->excludes(output);
    std::vector<std::string> formats{"json", "csv"};
    std::string help = "What a point query prints: json (one object), csv (a header and rows)";
    for (const auto& [name, what] : moreFormats) {
        formats.push_back(name);
        help += ", " + name + " (" + what + ")";
    }
    cmd->add_option("--point-format", o.format, help)->check(CLI::IsMember(formats))->capture_default_str();
}

std::optional<PointSpec> pointOf(const PointOptions& o) {
    if (!o.at.empty()) {
        const auto [lat, lon] = parsePair(o.at, "--at", "LAT,LON");
        return PointSpec{lat, lon, true};
    }
    if (!o.atXy.empty()) {
        const auto [x, y] = parsePair(o.atXy, "--at-xy", "X,Y");
        return PointSpec{x, y, false};
    }
    return std::nullopt;
}

void requireOutputOrPoint(const OutputOptions& out, const PointOptions& o) {
    if (out.path.empty() && !pointOf(o)) throw Error("-o OUT.tif is required (or --at / --at-xy for a point query)");
}

void refuseRasterOptions(const TilingOptions& tiling) {
    if (!tiling.srcwin.empty() || tiling.tileSize != "auto")
        throw Error("--srcwin and --tile-size apply to rasters, not to a point query (--at, --at-xy)");
}

DemSource openPointDem(const DemOptions& dem, const SearchRequest& search, const CliContext& ctx) {
    if (!search.maxDistanceM) return openDem(dem, ctx);
    // No bar for a point query's opening; Ctrl-C still stops it.
    return DemSource::openWithoutHeightPass(dem.path, dem.heights,
                                            [](double, const std::string&) { return !cancelRequested(); });
}

void refusePointCall(const PointOptions& o, const CliContext& ctx) {
    if (ctx.takeCall && pointOf(o)) throw Error("--at and --at-xy print values: run the command line for a point query");
}

nlohmann::ordered_json pointJson(const PointCell& p) {
    nlohmann::ordered_json j;
    j["x"] = p.x;
    j["y"] = p.y;
    j["column"] = p.cell.col;
    j["row"] = p.cell.row;
    j["cell_centre_x"] = p.centreX;
    j["cell_centre_y"] = p.centreY;
    j["latitude_deg"] = p.latitudeDeg;
    j["longitude_deg"] = p.longitudeDeg;
    j["height_m"] = p.heightM;
    return j;
}

void printPoint(const PointOptions& o, const nlohmann::ordered_json& json, const std::vector<std::string>& header,
                const std::vector<std::vector<std::string>>& rows) {
    if (o.format == "json") {
        std::cout << json.dump(2) << "\n";
        return;
    }
    const auto line = [](const std::vector<std::string>& cells) {
        std::string s;
        for (const std::string& c : cells) s += (s.empty() ? "" : ",") + c;
        return s + "\n";
    };
    std::cout << line(header);
    for (const auto& r : rows) std::cout << line(r);
}

}  // namespace demlight::cli
