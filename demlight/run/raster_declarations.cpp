// The declarations of the raster commands' parameters (demlight/run/raster_commands.h): one per
// command, in the order --help and QGIS's form show them.
#include "demlight/run/common_parameters.h"
#include "demlight/run/raster_commands.h"
#include "demlight/products/sunhours.h"

#include <stdexcept>

namespace demlight {

namespace {

/// The DEM, its heights and the output: every raster command's first parameters.
template <class P>
void declareInputAndOutput(RasterCommandOf<P>& c) {
    declareDem(c.declaration(), c.demPath);
    declareHeights(c.declaration(), c.values.heights);
    declareOutput(c.declaration(), c.out);
}

/// The search and tiling parameters: every raster command's last.
template <class P>
void declareSearchAndTiling(RasterCommandOf<P>& c) {
    declareSearch(c.declaration(), c.values.search, c.verbose);
    declareTiling(c.declaration(), c.values.tiling);
}

/// The number of horizon directions a sky or aperture integral takes, with its command's help.
Parameter& declareSkyDirections(ParameterSet& set, std::optional<std::size_t>& directions, const std::string& help) {
    return set.add("sky_directions", directions, "Sky directions", help).within(4, 1024).field("skyDirections");
}

const char* const kSunModelHelp =
    "Sun model: horizon (horizon angle in the sun's azimuth), aperture (sun cap intersected with the ambient-aperture "
    "cap), aperture-smooth (the same with the smoothstep intersection)";
const std::vector<std::string> kSunModels = {"horizon", "aperture", "aperture-smooth"};

void declareHorizon(RasterCommandOf<HorizonParameters>& c) {
    ParameterSet& set = c.declaration();
    HorizonParameters& p = c.values;
    declareInputAndOutput(c);
    set.add("azimuth", p.azimuthsDeg, "Azimuths (deg)", "True azimuth(s), degrees clockwise from north (repeatable)")
        .inUnit("deg")
        .notWith("directions")
        .field("azimuthsDeg");
    set.add("directions", p.directions, "Directions",
            "N azimuths evenly spaced from 0 (0, 360/N, ...); a point query without {azimuth}: 48")
        .within(1, 4096)
        .noDefault()
        .notWith("azimuth");
    declareSearchAndTiling(c);
    set.add("method", p.method, "Method", "sweep (fast, default) or reference (brute-force ray march)")
        .oneOf({"sweep", "reference"});
    set.add("output_type", p.dataType, "Horizon band type",
            "Horizon band type: Float32, or Int16 = 16-bit fixed point, -90..90 deg in steps of 0.00275 deg with "
            "GDAL scale/offset (readers get degrees), half the size")
        .flags("--ot")
        .oneOf({"Float32", "Int16"})
        .only(kCommandLine | kQgis);
}

void declareSun(RasterCommandOf<SunParameters>& c) {
    ParameterSet& set = c.declaration();
    SunParameters& p = c.values;
    declareInputAndOutput(c);
    declareTime(set, p.time, p.tz);
    declareSunDiameter(set, p.sunDiameterDeg);
    declareCanopy(set, p.canopy);
    set.add("pressure", p.atmosphere.pressureHpa, "Air pressure (hPa)", "Air pressure for solar refraction (hPa)")
        .within(0, kMaxPressureHpa)
        .inUnit("hPa")
        .field("pressureHpa")
        .forHowItRuns();
    set.add("temperature", p.atmosphere.temperatureC, "Air temperature (C)", "Air temperature for solar refraction (C)")
        .within(-100, 100)
        .inUnit("C")
        .field("temperatureC")
        .forHowItRuns();
    set.add("model", p.model, "Sun model", kSunModelHelp).oneOf(kSunModels);
    declareSkyDirections(set, p.directions,
                         "Aperture models: number of horizon directions integrated into the aperture (default: 16 "
                         "with {quality} auto, 64 with full); {directions} is the older spelling")
        .alias("directions");
    declareSearchAndTiling(c);
}

void declareSky(RasterCommandOf<SkyParameters>& c) {
    ParameterSet& set = c.declaration();
    SkyParameters& p = c.values;
    declareInputAndOutput(c);
    declareSkyDirections(set, p.directions,
                         "Number of horizon directions (sectors) integrated (default: 16 with {quality} auto, 64 "
                         "with full); {directions} is the older spelling")
        .alias("directions");
    set.add("albedo", p.albedo, "Ground albedo", "Constant ground albedo C for f_sky, in [0, 1]")
        .within(0.0, 1.0)
        .notWith("albedo_raster");
    set.add("albedo_raster", p.albedoRaster, "Ground albedo raster",
            "Albedo raster (band 1, 0-1), resampled bilinearly onto the DEM grid")
        .type("PATH")
        .notWith("albedo");
    set.add("patches", p.patches, "Sky patches",
            "Sky patches, one sky_K band each, summing to sky_K: 'sky' (one patch), 'sectors:N', "
            "'bands:E0,E1,...,90' (elevations, deg; the first band reaches down to -90), or 'sectors:N,bands:...'");
    set.add("model", p.model, "Sky model",
            "Sky model: stewart-langer (horizon-based SVF, K and f_sky) or hemisphere (Hargreaves (1 + N_up)/2 sky + "
            "albedo (1 - N_up)/2 ground, no occlusion)")
        .oneOf({"stewart-langer", "hemisphere"});
    declareSearchAndTiling(c);
}

void declareAperture(RasterCommandOf<ApertureParameters>& c) {
    ParameterSet& set = c.declaration();
    declareInputAndOutput(c);
    declareSkyDirections(set, c.values.directions,
                         "Number of horizon directions integrated (default: 16 with {quality} auto, 64 with full); "
                         "{directions} is the older spelling")
        .alias("directions");
    declareSearchAndTiling(c);
}

void declareLight(RasterCommandOf<LightParameters>& c) {
    ParameterSet& set = c.declaration();
    LightParameters& p = c.values;
    declareInputAndOutput(c);
    declareTime(set, p.time, p.tz);
    set.add("model", p.model, "Sun model", kSunModelHelp).oneOf(kSunModels);
    set.add("sky_model", p.skyModel, "Sky model", "stewart-langer, hemisphere or none")
        .oneOf({"stewart-langer", "hemisphere", "none"});
    declareSkyDirections(set, p.skyDirections,
                         "Horizon directions for the stewart-langer sky and the aperture models (default: 16 with "
                         "{quality} auto, 64 with full)");
    set.add("sun_color", p.sunColor, "Sun colour (R,G,B)", "Linear sun radiance R,G,B (gives three bands)");
    set.add("sky_color", p.skyColor, "Sky colour (R,G,B)", "Linear sky radiance R,G,B (gives three bands)");
    set.add("albedo", p.albedo, "Ground albedo", "Albedo C for interreflection (0-1; default 0.2)")
        .within(0.0, 1.0)
        .notWith("albedo_raster");
    set.add("albedo_raster", p.albedoRaster, "Ground albedo raster", "Per-cell albedo raster (band 1, 0-1)")
        .type("PATH")
        .notWith("albedo");
    declareColorRaster(set, p.colorRaster, p.colorEncoding,
                       "per-channel albedo for interreflection, and the output is albedo x light in three bands "
                       "reflected_r/g/b; excludes {albedo} and {albedo_raster}");
    set.add("cloud_shadow", p.cloudShadow, "Cloud shadow raster", "Raster multiplying the sun term (band 1, 0-1)")
        .type("PATH");
    declareCanopy(set, p.canopy);
    declareSunDiameter(set, p.sunDiameterDeg);
    declareSearchAndTiling(c);
}

void declareIrradiance(RasterCommandOf<IrradianceParameters>& c) {
    ParameterSet& set = c.declaration();
    IrradianceParameters& p = c.values;
    declareInputAndOutput(c);
    declareTime(set, p.time, p.tz);
    declareCanopy(set, p.canopy);
    declareClearSky(set, p.sky, "{time} in its zone");
    declareSkyDirections(set, p.skyDirections,
                         "Horizon directions of the visible sky (default: 16 with {quality} auto, 64 with full)");
    declareSunDiameter(set, p.sunDiameterDeg);
    declareSearchAndTiling(c);
}

void declareInsolation(RasterCommandOf<InsolationParameters>& c) {
    ParameterSet& set = c.declaration();
    InsolationParameters& p = c.values;
    declareInputAndOutput(c);
    declareDays(set, p.days, "IANA time zone of the days (required; UTC for universal time)");
    set.add("step", p.step, "Time step",
            "Time between sun positions (trapezoid weights), 6 s to 2 h: 10m, 90s, 1h (a bare number = minutes); "
            "they are binned, so a finer step costs little");
    declareCanopy(set, p.canopy);
    declareClearSky(set, p.sky, "each instant in {tz}");
    declareSkyDirections(set, p.directions,
                         "Azimuth sectors of the sun bins and of the visible sky: one horizon sweep each (default 64)")
        .field("directions");
    set.add("elevation_band", p.elevationBandDeg, "Elevation band (deg)", "Elevation band of the sun bins (degrees)")
        .within(0, 90, /*lowOpen=*/true)
        .inUnit("deg")
        .field("elevationBandDeg");
    declareSunDiameter(set, p.sunDiameterDeg);
    declareSearchAndTiling(c);
}

void declareSunhours(RasterCommandOf<SunhoursParameters>& c) {
    ParameterSet& set = c.declaration();
    SunhoursParameters& p = c.values;
    declareInputAndOutput(c);
    declareDays(set, p.days, "IANA time zone of the days and clock times (required; UTC for universal time)");
    set.add("step", p.step, "Time step",
            "Integration step (trapezoid rule), 6 s to 2 h: 10m, 90s, 1h (a bare number = minutes)");
    declareSunDiameter(set, p.sunDiameterDeg);
    declareCanopy(set, p.canopy);
    set.add("albedo", p.albedo, "Ground albedo", "Ground albedo C of the sky term f_sky = K / (1 - C(1 - K)) (0-1)")
        .within(0.0, 1.0);
    declareSkyDirections(set, p.skyDirections,
                         "Horizon directions of the sky term (default: 16 with {quality} auto, 64 with full)");
    set.add("horizon_mode", p.horizonMode, "Horizon mode",
            "auto, exact (a sweep per instant along its sun azimuth) or interpolated[:N] (N directions swept once, "
            "4..720, 64 by default; each instant's horizons interpolated in azimuth, and the sky term from the same N "
            "directions; close to exact, not the same bits). auto: interpolated for periods of " +
                std::to_string(kAutoStackMinInstants) +
                " instants or more (2 days at 10 min) on terrain under {quality} auto, where it costs less; else exact")
        .field("stackDirections");
    declareSearchAndTiling(c);
}

template <class P>
std::unique_ptr<RasterCommandOf<P>> make(const char* name, const char* description,
                                         typename RasterCommandOf<P>::Declare declare, RasterWork (*work)(const P&)) {
    return std::make_unique<RasterCommandOf<P>>(name, description, declare, work);
}

}  // namespace

std::unique_ptr<RasterCommandOf<HorizonParameters>> horizonCommand() {
    return make<HorizonParameters>("horizon", "Horizon elevation angle maps along true azimuths", declareHorizon,
                                   [](const HorizonParameters& p) { return rasterWork(horizonWork(p)); });
}

std::unique_ptr<RasterCommandOf<SunParameters>> sunCommand() {
    return make<SunParameters>("sun", "Sun visibility and direct-sun irradiance at one instant", declareSun,
                               [](const SunParameters& p) { return rasterWork(sunWork(p)); });
}

std::unique_ptr<RasterCommandOf<SkyParameters>> skyCommand() {
    return make<SkyParameters>("sky", "Sky-view factors and skylight K / f_sky", declareSky,
                               [](const SkyParameters& p) { return rasterWork(skyWork(p)); });
}

std::unique_ptr<RasterCommandOf<ApertureParameters>> apertureCommand() {
    return make<ApertureParameters>("aperture", "Ambient aperture: bent normal, cap radius, visible solid angle",
                                    declareAperture,
                                    [](const ApertureParameters& p) { return rasterWork(apertureWork(p)); });
}

std::unique_ptr<RasterCommandOf<LightParameters>> lightCommand() {
    return make<LightParameters>("light", "Combined sun + sky lightmap at one instant (Float32, linear)", declareLight,
                                 [](const LightParameters& p) { return rasterWork(lightWork(p)); });
}

std::unique_ptr<RasterCommandOf<IrradianceParameters>> irradianceCommand() {
    return make<IrradianceParameters>(
        "irradiance", "Clear-sky solar irradiance (W/m2) at one instant: beam, diffuse, reflected, global (ESRA)",
        declareIrradiance, [](const IrradianceParameters& p) { return rasterWork(irradianceWork(p)); });
}

std::unique_ptr<RasterCommandOf<InsolationParameters>> insolationCommand() {
    return make<InsolationParameters>(
        "insolation",
        "Clear-sky solar irradiation (kWh/m2) over a period, from an interval within a day to a year: beam, diffuse, "
        "reflected, global, and hours of direct sun",
        declareInsolation, [](const InsolationParameters& p) { return rasterWork(insolationWork(p)); });
}

std::unique_ptr<RasterCommandOf<SunhoursParameters>> sunhoursCommand() {
    return make<SunhoursParameters>(
        "sunhours", "Hours of direct sun, sun and sky irradiation and first/last lit time over local days",
        declareSunhours, [](const SunhoursParameters& p) { return rasterWork(sunhoursWork(p)); });
}

namespace {

/// The raster commands' makers, in the order the command line lists them.
using RasterCommandMaker = std::unique_ptr<RasterCommand> (*)();
const std::vector<RasterCommandMaker>& rasterCommandMakers() {
    static const std::vector<RasterCommandMaker> makers = {
        []() -> std::unique_ptr<RasterCommand> { return horizonCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return sunCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return skyCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return apertureCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return lightCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return irradianceCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return insolationCommand(); },
        []() -> std::unique_ptr<RasterCommand> { return sunhoursCommand(); },
    };
    return makers;
}

}  // namespace

const std::vector<std::string>& rasterCommandNames() {
    // The names their declarations give, not a second spelling of them.
    static const std::vector<std::string> names = [] {
        std::vector<std::string> out;
        for (const RasterCommandMaker make : rasterCommandMakers()) out.push_back(make()->declaration().command());
        return out;
    }();
    return names;
}

std::unique_ptr<RasterCommand> makeRasterCommand(const std::string& name) {
    const std::vector<std::string>& names = rasterCommandNames();
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return rasterCommandMakers()[i]();
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error("'" + name + "' is not a raster command (" + list + ")");
}

}  // namespace demlight
