// demlight quicklook RASTER -o OUT.png [--band N|NAME]: one band of any raster (demlight's outputs
// above all) as a picture with a colour bar and a title (demlight/products/quicklook.h).
#include "cli/common.h"
#include "cli/declared.h"
#include "demlight/geo/image_out.h"
#include "demlight/products/quicklook.h"

#include <sstream>

namespace demlight::cli {
namespace {

struct QuicklookOptions {
    ParameterSet set{"quicklook", "Picture of one band of a raster: colour map, colour bar with its unit, title"};
    std::string input, outPath, band = "1", range, title;
    std::size_t size = QuicklookRequest{}.mapSize;
};

std::pair<double, double> parseRange(const std::string& text) {
    const auto bad = [&] { return Error("--range '" + text + "': expected LOW,HIGH with LOW < HIGH, like 0,2800"); };
    std::stringstream ss(text);
    std::string low, high, extra;
    if (!std::getline(ss, low, ',') || !std::getline(ss, high, ',') || std::getline(ss, extra, ',')) throw bad();
    const std::optional<double> lo = parseFiniteNumber(low), hi = parseFiniteNumber(high);
    if (!lo || !hi || !(*lo < *hi)) throw bad();
    return {*lo, *hi};
}

void runQuicklook(const QuicklookOptions& o, const CliContext& ctx) {
    QuicklookRequest request;
    request.path = o.input;
    request.band = o.band;
    if (!o.range.empty()) request.range = parseRange(o.range);
    request.mapSize = o.size;
    request.title = o.title;
    checkOutputPath(o.outPath, o.input);
    checkImagePath(o.outPath);
    const QuicklookResult r = quicklookProduct(request);
    writeImage(o.outPath, r.image);
    note(ctx, "wrote " + o.outPath + " (" + std::to_string(r.image.width) + " x " + std::to_string(r.image.height) +
                  "): band " + std::to_string(r.band.index) +
                  (r.band.description.empty() ? "" : " (" + r.band.description + ")") + ", colours from " +
                  formatNumber(r.low) + " to " + formatNumber(r.high) + (r.unitLabel.empty() ? "" : " " + r.unitLabel) +
                  (o.range.empty() ? " (its 1st and 99th percentiles)" : ""));
}

}  // namespace

void registerQuicklook(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<QuicklookOptions>();
    ParameterSet& set = o->set;
    set.add("raster", o->input, "Raster", "Raster to look at (any GDAL raster; demlight's outputs name their bands)")
        .positionalAs("RASTER")
        .mandatory();
    declarePictureOutput(set, o->outPath, ".png, .jpg");
    set.add("band", o->band, "Band", "Band: its number (1 = first) or its description (e.g. global)").type("N|NAME");
    set.add("range", o->range, "Colour map range (low,high)",
            "Values at the ends of the colour map (default: the 1st and 99th percentiles)")
        .type("LOW,HIGH");
    set.add("size", o->size, "Map size (pixels)", "Longer side of the map in pixels (the title and bar are added)")
        .within(16, 16384)
        .field("mapSize");
    set.add("title", o->title, "Title", "Title (default: product, band and time or period from the file's metadata)");
    notInPython(set);
    CLI::App* cmd = addDeclaredCommand(app, set, ctx);
    ctx.outputs[cmd->get_name()].kind = "picture";
    cmd->callback([o, &ctx] { runQuicklook(*o, ctx); });
}

}  // namespace demlight::cli
