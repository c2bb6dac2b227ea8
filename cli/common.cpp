#include "cli/common.h"

#include "cli/progress_bar.h"
#include "demlight/geo/output_file.h"
#include "demlight/geo/time.h"
#include "demlight/core/error.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <strings.h>
#include <unistd.h>

namespace demlight::cli {

namespace fs = std::filesystem;

RunContext runContext(const CliContext& ctx) {
    RunContext run;
    run.commandLine = ctx.commandLine;
    if (!ctx.quiet) run.notes = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
    run.cancelled = [] { return cancelRequested(); };
    return run;
}

DemSource openDem(const DemOptions& o, const CliContext& ctx) { return openDem(o.path, o.heights, ctx); }

DemSource openDem(const std::string& path, const HeightOptions& heights, const CliContext& ctx) {
    ProgressBar bar(!ctx.quiet);
    DemSource source = DemSource::open(path, heights, bar.callback());
    bar.finish();
    return source;
}

void notePlan(const SearchOptions& o, const Terrain& terrain, const CliContext& ctx) {
    notePlan(o.request, o.verbose, terrain, ctx);
}

void notePlan(const SearchRequest& request, bool verbose, const Terrain& terrain, const CliContext& ctx) {
    const ScenePlan plan = planFor(request, terrain);
    if (plan.quality == Quality::Full && request.toleranceDeg != kDefaultToleranceDeg)
        note(ctx, "note: --tolerance is not used by --quality full (every effect at its finest setting)");
    if (verbose && !ctx.quiet) {
        note(ctx, "scene plan (--quality " + std::string(qualityName(plan.quality)) + "):");
        for (const auto& r : plan.reasons) note(ctx, "  " + r);
        note(ctx, "  expected horizon error: " + describeExpectedError(plan.expectedError));
    }
}

void declareDemOptions(ParameterSet& set, DemOptions& o) {
    declareDem(set, o.path);
    declareHeights(set, o.heights);
}

void declareSearchOptions(ParameterSet& set, SearchOptions& o) { declareSearch(set, o.request, o.verbose); }

void declarePictureOptions(ParameterSet& set, PictureOptions& o) {
    declareColorRaster(set, o.colorRaster, o.colorEncoding, "the albedo of the picture");
    set.add("albedo", o.albedo, "Albedo", "Linear albedo without a colour raster").within(0.0, 1.0);
    set.add("exposure", o.exposure, "Exposure", "Multiplies linear light before gamma").within(0.0, 1000.0);
    set.add("pixels", o.pixels, "Pixels",
            "ground: square ground pixels (lat/lon DEMs are resampled east-west); cell: one pixel per DEM cell")
        .oneOf({"ground", "cell"});
}

void declarePictureOutput(ParameterSet& set, std::string& path, const std::string& extensions) {
    set.add("output", path, "Output picture", "Output picture; format from the extension (" + extensions + ")")
        .flags("-o,--output")
        .type("OUT.png")
        .mandatory();
}

void notInPython(ParameterSet& set) {
    for (Parameter& p : set.parameters()) p.frontEnds &= ~unsigned(kPython);
}

void commandLineOnly(ParameterSet& set) {
    for (Parameter& p : set.parameters()) p.frontEnds = kCommandLine;
}

PictureRequest pictureRequest(const PictureOptions& o) {
    PictureRequest r;
    r.colorRaster = o.colorRaster;
    r.colorEncoding = parseColorEncoding(o.colorEncoding, "color_encoding");
    r.albedo = o.albedo;
    r.exposure = o.exposure;
    r.pixels = o.pixels == "cell" ? PixelGeometry::Cell : PixelGeometry::Ground;
    return r;
}

std::string formatSeconds(double seconds) {
    // Below a tenth of a second, milliseconds (small DEMs would print "0 s").
    if (seconds < 0.1) return formatNumber(std::round(seconds * 1e4) / 10) + " ms";
    return formatNumber(std::round(seconds * 100) / 100) + " s";
}

std::string formatDistance(double metres) {
    return std::isfinite(metres) ? formatNumber(std::round(metres)) + " m" : std::string("the whole DEM");
}

void note(const CliContext& ctx, const std::string& line) {
    if (!ctx.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

}  // namespace demlight::cli
