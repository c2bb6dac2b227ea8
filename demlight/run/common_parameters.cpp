#include "demlight/run/common_parameters.h"

#include "demlight/geo/raster.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"

#include <limits>
#include <strings.h>

namespace demlight {

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();
constexpr unsigned kCommandLineAndQgis = kCommandLine | kQgis;

}  // namespace

void declareDem(ParameterSet& set, std::string& path) {
    set.add("dem", path, "DEM", "Input DEM: any raster GDAL opens, /vsizip/ and other virtual paths included")
        .positionalAs("DEM")
        .mandatory()
        .only(kCommandLineAndQgis);
}

void declareHeights(ParameterSet& set, HeightOptions& heights) {
    set.add("z_unit", heights.zUnit, "Vertical unit",
            "Vertical unit of the heights instead of the band's own (m, ft, US survey foot, cm, dm, mm, km)")
        .notWith("z_factor")
        .forHowItRuns();
    set.add("z_factor", heights.zFactor, "Metres per height unit",
            "Metres per height unit (after the band's scale and offset), instead of converting a unit")
        .within(0, kUnbounded, /*lowOpen=*/true)
        .noDefault()
        .notWith("z_unit")
        .forHowItRuns();
}

void declareOutput(ParameterSet& set, OutputOptions& out) {
    set.add("output", out.path, "Output raster", "Output raster path")
        .flags("-o,--output")
        .inPython("path")
        .type("OUT.tif")
        .mandatory()
        .only(kCommandLineAndQgis);
    set.add("format", out.format, "Output format",
            "Output format: GTiff (tiled, ZSTD level 1, band-interleaved) or COG (DEFLATE)")
        .flags("--of")
        .oneOf({"GTiff", "COG"})
        .check([](std::string& v) -> std::string {
            // GDAL's driver names in any case, as gdal_translate -of takes them.
            for (const char* name : {"GTiff", "COG"})
                if (strcasecmp(v.c_str(), name) == 0) v = name;
            return {};
        })
        .only(kCommandLineAndQgis);
    set.add("creation_options", out.creationOptions, "GDAL creation options",
            "GDAL creation option KEY=VALUE (repeatable), e.g. COMPRESS=DEFLATE for readers without ZSTD; block "
            "sides (BLOCKXSIZE, BLOCKYSIZE, BLOCKSIZE) 1 to " + std::to_string(kMaxBlockSideCells) + " cells")
        .flags("--co")
        .type("KEY=VALUE")
        .check([](std::string& v) { return blockSizeProblem(v); })
        .only(kCommandLineAndQgis)
        .forHowItRuns();
}

void declareSearch(ParameterSet& set, SearchRequest& r, bool& verbose) {
    set.add("max_distance", r.maxDistanceM, "Max distance (m)",
            "Horizon search distance (metres). Default ({quality} auto): relief / tan(2 deg), or the whole DEM when "
            "that is half its diagonal or more (sky and aperture integrals: the whole DEM unless a range limit saves "
            "sweep work); full: the whole DEM")
        .within(0, kUnbounded, /*lowOpen=*/true)
        .inUnit("m")
        .field("maxDistanceM");
    set.add("refraction", r.refraction, "Refraction coefficient",
            "Refraction coefficient k for terrain sight lines; earth radius R/(1-k); 0 = pure geometry")
        .within(0.0, 0.99)
        .forHowItRuns();
    set.add("threads", r.threads, "Threads", "Worker threads (0 = all cores; at most the cores are used)")
        .within(0, kUnbounded)
        .forHowItRuns();
    set.addText("quality", [&r](const std::string& name) { r.quality = parseQuality(name); }, "Quality",
                "auto: model only what the scene needs within {tolerance}; full: every effect at its finest setting")
        .oneOf({"auto", "full"})
        .byDefault("auto");
    set.add("tolerance", r.toleranceDeg, "Horizon tolerance (deg)",
            "Horizon error budget for {quality} auto (degrees): decides curvature and the scan-direction tolerance; "
            "a looser one is added to the stated error")
        .within(0.001, 10.0)
        .inUnit("deg")
        .field("toleranceDeg")
        .forHowItRuns();
    set.add("near_field", r.nearFieldSteps, "Near field (line steps)",
            "Horizon near field (line steps, 0-32): terrain this close is sampled on the ray from each cell's own "
            "centre, farther terrain by scan lines. Default: 16 on surface models (buildings, trees: 5 % or more of "
            "neighbour steps steeper than 45 deg), 4 on terrain; 0 = scan lines only (the model of earlier releases)")
        .within(0, kMaxNearFieldSteps)
        .field("nearFieldSteps")
        .forHowItRuns();
    set.add("verbose", verbose, "Verbose", "Print the modelling choices (the scene plan) and the peak memory")
        .flags("-v,--verbose")
        .only(kCommandLine);
}

void declareTiling(ParameterSet& set, TilingOptions& o) {
    set.add("tile_size", o.tileSize, "Tile size (cells)",
            "Compute in tiles of N x N cells, each with the halo its search needs, writing each as it completes; the "
            "output is bit for bit the one-piece output. auto: one piece unless that exceeds {memory_limit}")
        .forHowItRuns();
    set.add("memory_limit", o.memoryLimitMB, "Memory limit (MB)",
            "Peak memory (MB) of the whole process that {tile_size} auto plans for: the program, the pass over the "
            "DEM's heights and each tile must fit; a run that cannot is refused, naming the smallest limit that fits "
            "(default: half of this machine's memory)")
        .within(16, 1e9)
        .inUnit("MB")
        .noDefault()
        .forHowItRuns();
    set.add("srcwin", o.srcwin, "Source window (cells)",
            "Compute only the window XOFF YOFF XSIZE YSIZE (cells, as gdal_translate -srcwin), reading the halo it "
            "needs; its output has the window's georeference, and windows mosaicked with gdalbuildvrt equal the "
            "one-piece output bit for bit")
        .values(4, 4)
        .within(0, kUnbounded)
        .forHowItRuns();
}

void declareTime(ParameterSet& set, std::string& time, std::string& tz) {
    set.add("time", time, "Time",
            "Instant: ISO 8601 with offset or Z (2024-06-21T05:30:00+02:00), or local time with {tz}")
        .type("TIME")
        .mandatory();
    set.add("tz", tz, "Time zone", "IANA time zone for a local {time} (e.g. Europe/Zurich)").field("zone");
}

void declareDays(ParameterSet& set, DayOptions& o, const std::string& tzHelp) {
    set.add("date", o.date, "Day", "Local day YYYY-MM-DD (midnight to midnight in {tz})");
    if (o.periods) {
        set.add("start", o.startDate, "Start",
                "Start of a range: a first local day YYYY-MM-DD, or a local time YYYY-MM-DDTHH:MM[:SS]")
            .field("firstDay");
        set.add("end", o.endDate, "End",
                "End of a range: a last local day YYYY-MM-DD (inclusive), or a local time YYYY-MM-DDTHH:MM[:SS]")
            .field("lastDay")
            .field("interval");
        set.add("month", o.month, "Month", "Local calendar month YYYY-MM");
        set.add("year", o.year, "Year", "Local calendar year YYYY");
    } else {
        set.add("start", o.startDate, "First day", "First local day YYYY-MM-DD of a range").field("firstDay");
        set.add("end", o.endDate, "Last day", "Last local day YYYY-MM-DD of a range (inclusive)").field("lastDay");
    }
    set.add("tz", o.tz, "Time zone", tzHelp).field("zone");
}

void declareSunDiameter(ParameterSet& set, double& diameterDeg) {
    set.add("sun_diameter", diameterDeg, "Sun diameter (deg)",
            "Angular diameter of the sun disk (degrees); larger = softer shadows")
        .within(0.0, 20.0)
        .inUnit("deg")
        .field("sunDiameterDeg");
}

void declareCanopy(ParameterSet& set, CanopyRequest& canopy) {
    set.add("canopy", canopy.raster, "Canopy height raster",
            "Vegetation height above ground (metres, 0-150) on the DEM, a surface model with the trees on it: where "
            "the sun's line passes only through crowns, {transmissivity} of the beam gets through (and of the sky "
            "they hide); cells under a crown are lit on the ground below it (any raster GDAL opens, band 1, resampled "
            "bilinearly; nodata = no vegetation)")
        .type("PATH")
        .field("canopyRaster");
    set.add("transmissivity", canopy.transmissivity, "Canopy transmissivity",
            "Share of the light that passes through the crowns of {canopy} (0-1; SOLWEIG's default)")
        .within(0.0, 1.0);
}

void declareColorRaster(ParameterSet& set, std::string& path, std::string& encoding, const std::string& use) {
    set.add("color_raster", path, "Colour raster",
            "Colour raster (R, G, B bands, or one grey band), resampled onto the DEM: " + use);
    set.add("color_encoding", encoding, "Colour encoding",
            "How {color_raster} holds colour: srgb (display-encoded 0-255 or 0-1, decoded with gamma 2.2), linear "
            "(albedo 0-1), or auto (srgb when any value exceeds 1, else linear)")
        .oneOf({"auto", "srgb", "linear"});
}

void declareClearSky(ParameterSet& set, ClearSkyOptions& o, const std::string& monthOf) {
    set.add("linke", o.linke, "Linke turbidity",
            "Linke turbidity factor (air mass 2, 1-10): one value, or 12 comma-separated monthly values (January "
            "first) of which the month of " + monthOf + " is used");
    set.add("albedo", o.albedo, "Ground albedo", "Ground albedo of the reflected component (0-1)").within(0.0, 1.0);
    set.add("coeff_bh", o.coeffBh, "Real-sky beam index",
            "Real-sky beam index: fraction of the clear-sky beam that reaches the ground (0-1, r.sun coeff_bh)")
        .within(0.0, 1.0);
    set.add("coeff_dh", o.coeffDh, "Real-sky diffuse index",
            "Real-sky diffuse index: fraction of the clear-sky diffuse that reaches the ground (0-1, r.sun coeff_dh)")
        .within(0.0, 1.0);
    // r.sun's linke, albedo, coeff_bh and coeff_dh maps: one raster each, resampled bilinearly.
    const std::string resampled =
        " (band 1, any raster GDAL opens; resampled bilinearly onto the DEM's grid; nodata where it has none)";
    set.add("linke_raster", o.linkeRaster, "Linke turbidity raster",
            "Linke turbidity per cell, 1-10, instead of {linke}: a raster of one band, or of 12 monthly bands (band "
            "m = month m, January first) of which the month of " + monthOf +
                " is used; or the parameter given 12 times, one one-band raster per month, January first (any raster "
                "GDAL opens; resampled bilinearly onto the DEM's grid; nodata where it has none)")
        .type("PATH")
        .notWith("linke");
    set.add("albedo_raster", o.albedoRaster, "Ground albedo raster",
            "Ground albedo per cell, 0-1, instead of {albedo}" + resampled)
        .type("PATH")
        .notWith("albedo");
    set.add("coeff_bh_raster", o.coeffBhRaster, "Real-sky beam index raster",
            "Real-sky beam index per cell, 0-1, instead of {coeff_bh}" + resampled)
        .type("PATH")
        .notWith("coeff_bh");
    set.add("coeff_dh_raster", o.coeffDhRaster, "Real-sky diffuse index raster",
            "Real-sky diffuse index per cell, 0-1, instead of {coeff_dh}" + resampled)
        .type("PATH")
        .notWith("coeff_dh");
    set.add("diffuse_model", o.diffuseModel, "Diffuse model",
            "visible-sky: diffuse horizontal x the sky the horizons leave above the horizontal, reflected from the "
            "rest of the view; rsun: r.sun's Muneer tilted-surface diffuse and (1 - cos slope)/2 reflected")
        .oneOf({"visible-sky", "rsun"});
    set.add("solar_constant", o.solarConstantWm2, "Solar constant (W/m2)",
            "Solar constant (W/m2); the extraterrestrial irradiance is this / R^2 at the sun-earth distance R")
        .within(1000, 1500)
        .inUnit("W/m2")
        .field("solarConstantWm2");
}

}  // namespace demlight
