// demlight sun DEM -o OUT.tif --time T [--tz ZONE]: how much of the sun's disk each cell sees.
//
// Sun position per region: SPA is evaluated on a lattice of cells every 64 cells (geo/
// sun_field.h); every cell takes its own interpolated sun elevation and azimuth for visibility
// and N·s. The horizon sweep needs one azimuth per region: the DEM is split into tiles (halving
// the longer side) until the sun's azimuth varies by at most kSunAzimuthToleranceDeg within a
// tile, and each tile is swept along its centre azimuth (occluders from the whole DEM).
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/sun_field.h"
#include "geo/time.h"
#include "lighting/horizon.h"
#include "lighting/sun.h"
#include "lighting/surface.h"
#include "src/angles.h"
#include "src/error.h"
#include "src/parallel.h"

#include <chrono>
#include <cmath>

namespace demlight::cli {
namespace {

/// Largest spread of the sun's azimuth inside one swept tile (degrees). The horizon changes
/// with azimuth by well under 1 deg per deg on real terrain, so this keeps the horizon error
/// from a shared azimuth below about 0.05 deg.
constexpr double kSunAzimuthToleranceDeg = 0.1;
/// Tiles are not split below this many cells on a side.
constexpr std::size_t kMinTileCells = 64;
/// Lowest sun elevation used to size the default search distance (degrees).
constexpr double kLowestShadowElevationDeg = 0.25;

struct SunOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::string time;
    std::string tz;
    double sunDiameterDeg = kSunDiameterDeg;
    double pressureHpa = 1013.25;
    double temperatureC = 15;
};

void splitTiles(const SunField& field, CellWindow w, std::vector<CellWindow>& tiles) {
    const auto [lo, hi] = field.azimuthRange(w.col0, w.row0, w.col1, w.row1);
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    if (hi - lo <= kSunAzimuthToleranceDeg || std::max(cols, rows) < 2 * kMinTileCells) {
        tiles.push_back(w);
        return;
    }
    CellWindow a = w, b = w;
    if (cols >= rows) {
        a.col1 = b.col0 = w.col0 + cols / 2;
    } else {
        a.row1 = b.row0 = w.row0 + rows / 2;
    }
    splitTiles(field, a, tiles);
    splitTiles(field, b, tiles);
}

/// Search distance that catches every shadow: relief / tan(lowest sun elevation minus the
/// disk's radius), at least 0.25 deg, capped by the DEM diagonal.
double sunSearchDistanceM(const Terrain& t, double lowestSunDeg, double sunDiameterDeg) {
    const auto [lo, hi] = heightRangeM(t.heightsM);
    const double angle = std::max(lowestSunDeg - sunDiameterDeg / 2, kLowestShadowElevationDeg);
    double diag2 = 0;
    const double widthM = t.cellWidthM[t.height() / 2] * static_cast<double>(t.width());
    double heightM = 0;
    for (double h : t.cellHeightM) heightM += h;
    diag2 = widthM * widthM + heightM * heightM;
    const double byRelief = static_cast<double>(hi - lo) / std::tan(angle * kDegToRad);
    return std::max(t.cellHeightM.front(), std::min(byRelief, std::sqrt(diag2)));
}

void runSun(const SunOptions& o, const CliContext& ctx) {
    const ZonedInstant when = parseZonedInstant(o.time, o.tz);
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;

    SolarSite site;
    site.pressureHpa = o.pressureHpa;
    site.temperatureC = o.temperatureC;
    const SunField field = computeSunField(dem, when.utc, site, SpaOptions{});
    double lowestSun = 90, highestSun = -90;
    for (float e : field.elevationDeg.values())
        lowestSun = std::min<double>(lowestSun, e), highestSun = std::max<double>(highestSun, e);

    HorizonParams params;
    params.refraction = o.search.refraction;
    params.threads = o.search.threads;
    params.maxDistanceM = o.search.maxDistanceM.value_or(
        sunSearchDistanceM(t, lowestSun, o.sunDiameterDeg));

    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    Grid<float> visibility(t.width(), t.height(), std::numeric_limits<float>::quiet_NaN());
    Grid<float> irradiance = visibility;

    std::vector<CellWindow> tiles;
    const bool sunUp = highestSun > -o.sunDiameterDeg / 2;
    if (sunUp) splitTiles(field, {0, 0, t.width(), t.height()}, tiles);

    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "sun", t.heightsM.size());
    for (const CellWindow& tile : tiles) {
        const auto [azLo, azHi] = field.azimuthRange(tile.col0, tile.row0, tile.col1, tile.row1);
        params.azimuthDeg = wrapAzimuthDeg(0.5 * (azLo + azHi));
        params.window = tile;
        const HorizonMap horizon = sweepHorizon(t, params, &counter);
        parallelFor(tile.row0, tile.row1, o.search.threads, [&](std::size_t row) {
            for (std::size_t col = tile.col0; col < tile.col1; ++col) {
                const float h = horizon.angleDeg(col, row);
                if (std::isnan(h)) continue;
                const auto [az, el] = field.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5);
                const Enu n = normals.at(col, row);
                visibility(col, row) = static_cast<float>(
                    sunVisibilityClamped(n, h, wrapAzimuthDeg(az), el, o.sunDiameterDeg));
                irradiance(col, row) = static_cast<float>(
                    sunIrradiance(n, h, wrapAzimuthDeg(az), el, o.sunDiameterDeg));
            }
        });
    }
    if (!sunUp) {
        for (std::size_t i = 0; i < visibility.size(); ++i)
            if (!std::isnan(t.heightsM.data()[i])) visibility.data()[i] = irradiance.data()[i] = 0.0f;
    }
    bar.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const std::map<std::string, std::string> meta = {
        {"DEMLIGHT_PRODUCT", "sun"},
        {"DEMLIGHT_TIME_UTC", formatInstant(when.utc, std::string())},
        {"DEMLIGHT_TIME_LOCAL", formatInstant(when.utc, when.zone)},
        {"DEMLIGHT_SUN_AZIMUTH_DEG", formatNumber(field.centre.azimuthDeg)},
        {"DEMLIGHT_SUN_ELEVATION_DEG", formatNumber(field.centre.elevationDeg)},
        {"DEMLIGHT_SUN_ELEVATION_RANGE_DEG", formatNumber(lowestSun) + "," + formatNumber(highestSun)},
        {"DEMLIGHT_SUN_REGIONS", std::to_string(tiles.size())},
        {"DEMLIGHT_SUN_DIAMETER_DEG", formatNumber(o.sunDiameterDeg)},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_MAX_DISTANCE_M", formatNumber(params.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(params.refraction)},
    };
    writeRaster(o.out.path,
                {{&visibility, nullptr, "sun_visibility", "fraction of sun disk (0-1)"},
                 {&irradiance, nullptr, "sun_irradiance",
                  "normalised irradiance (1 = unit-radiance zenith sun on flat ground)"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "sun at DEM centre: azimuth " + formatNumber(field.centre.azimuthDeg) +
                  " deg, elevation " + formatNumber(field.centre.elevationDeg) + " deg (" +
                  formatInstant(when.utc, std::string()) + ")" +
                  (sunUp ? "" : "; the sun is below the horizon: everything is in shadow"));
    note(ctx, "wrote " + o.out.path + " (band 1 sun_visibility, band 2 sun_irradiance); " +
                  std::to_string(tiles.size()) + " sun region(s), max distance " +
                  formatNumber(std::round(params.maxDistanceM)) + " m, " + formatNumber(seconds) +
                  " s compute");
}

}  // namespace

void registerSun(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<SunOptions>();
    CLI::App* cmd = app.add_subcommand("sun", "Sun visibility and direct-sun irradiance at one instant");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--time", o->time,
                    "Instant: ISO 8601 with offset or Z (2024-06-21T05:30:00+02:00), or local "
                    "time with --tz")
        ->required();
    cmd->add_option("--tz", o->tz, "IANA time zone for a local --time (e.g. Europe/Zurich)");
    cmd->add_option("--sun-diameter", o->sunDiameterDeg,
                    "Angular diameter of the sun disk (degrees); larger = softer shadows")
        ->check(CLI::Range(0.0, 20.0))
        ->capture_default_str();
    cmd->add_option("--pressure", o->pressureHpa, "Air pressure for solar refraction (hPa)")
        ->check(CLI::Range(0.0, 1200.0))
        ->capture_default_str();
    cmd->add_option("--temperature", o->temperatureC, "Air temperature for solar refraction (C)")
        ->check(CLI::Range(-100.0, 60.0))
        ->capture_default_str();
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runSun(*o, ctx); });
}

}  // namespace demlight::cli
