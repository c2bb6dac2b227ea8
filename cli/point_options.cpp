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

void declarePointOptions(ParameterSet& set, PointOptions& o,
                         const std::vector<std::pair<std::string, std::string>>& moreFormats) {
    set.find("output")->required = false;  // a point query prints instead
    set.add("at", o.at, "Point (lat, lon)",
            "Point query: print the values at WGS84 LAT,LON (degrees; --at=-33.9,18.4 when the first is negative) "
            "instead of writing a raster")
        .type("LAT,LON")
        .notWith("at_xy")
        .notWith("output")
        .field("point")
        .only(kCommandLine);
    set.add("at_xy", o.atXy, "Point (x, y)", "Point query at X,Y in the DEM's CRS (as {at})")
        .type("X,Y")
        .notWith("at")
        .notWith("output")
        .only(kCommandLine);
    std::vector<std::string> formats{"json", "csv"};
    std::string help = "What a point query prints: json (one object), csv (a header and rows)";
    for (const auto& [name, what] : moreFormats) {
        formats.push_back(name);
        help += ", " + name + " (" + what + ")";
    }
    set.add("point_format", o.format, "Point output format", help).oneOf(formats).only(kCommandLine);
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
