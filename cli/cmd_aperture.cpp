// demlight aperture DEM -o OUT.tif: ambient aperture per cell (Oat & Sander 2007): the visible
// solid angle, the spherical cap of the same area and its axis, the bent normal.
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "lighting/aperture.h"
#include "lighting/directions.h"
#include "lighting/surface.h"

#include <chrono>
#include <optional>

namespace demlight::cli {
namespace {

/// Default --directions: kDefaultSkyDirections (lighting/sky.h), as for `demlight sky`: the
/// aperture's solid angle and bent normal converge with the direction count like sky_K does
/// (README "Sky accuracy").
constexpr int kDefaultApertureDirections = static_cast<int>(kDefaultSkyDirections);

struct ApertureOptions {
    std::string demPath;
    OutputOptions out;
    SearchOptions search;
    std::optional<int> directions;  ///< default: the scene plan's (kDefaultApertureDirections for auto)
};

void runAperture(const ApertureOptions& o, const CliContext& ctx) {
    checkOutputPath(o.out.path, o.demPath);
    const Dem dem = loadDem(o.demPath);
    const Terrain& t = dem.terrain;
    const ScenePlan plan = planFor(o.search, t, kDefaultLowestElevationDeg, ctx);
    const int directions = o.directions.value_or(plan.skyDirections);
    const HorizonParams params = integralParams(o.search, plan, t, static_cast<std::size_t>(directions));

    const auto start = std::chrono::steady_clock::now();
    const Normals normals = computeNormals(t, o.search.threads);
    ApertureAccumulator acc(normals.east, normals.north, normals.up,
                            static_cast<std::size_t>(directions), o.search.threads);
    ProgressBar bar(!ctx.quiet);
    ProgressCounter counter(bar.callback(), "aperture", t.heightsM.size() * static_cast<std::size_t>(directions));
    sweepDirections(t, params, static_cast<std::size_t>(directions),
                    [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); },
                    &counter);
    const ApertureMaps maps = acc.finish();
    bar.finish();
    const double seconds = secondsSince(start);

    std::map<std::string, std::string> meta = planMetadata(plan);
    meta.insert({
        {"DEMLIGHT_PRODUCT", "aperture"},
        {"DEMLIGHT_METHOD", "sweep"},
        {"DEMLIGHT_DIRECTIONS", std::to_string(directions)},
        {"DEMLIGHT_MAX_DISTANCE_M", metadataDistanceM(dem.terrain, params.maxDistanceM)},
        {"DEMLIGHT_REFRACTION", formatNumber(params.refraction)},
    });
    writeRaster(o.out.path,
                {{&maps.bentEast, nullptr, "bent_normal_east", "unit vector component (ENU)"},
                 {&maps.bentNorth, nullptr, "bent_normal_north", "unit vector component (ENU)"},
                 {&maps.bentUp, nullptr, "bent_normal_up", "unit vector component (ENU)"},
                 {&maps.radiusDeg, nullptr, "aperture_radius_deg", "deg"},
                 {&maps.solidAngleSr, nullptr, "visible_solid_angle_sr", "sr"}},
                dem.band.ref, makeWriteOptions(o.out, ctx, dem, meta), o.demPath);
    note(ctx, "wrote " + o.out.path + " (bent normal E/N/U, aperture radius, visible solid angle); " +
                  std::to_string(directions) + " directions, " + formatSeconds(seconds) + " compute");
}

}  // namespace

void registerAperture(CLI::App& app, CliContext& ctx) {
    auto o = std::make_shared<ApertureOptions>();
    CLI::App* cmd = app.add_subcommand("aperture", "Ambient aperture: bent normal, cap radius, visible solid angle");
    cmd->add_option("DEM", o->demPath, "Input DEM")->required()->check(CLI::ExistingFile);
    addOutputOptions(cmd, o->out);
    cmd->add_option("--directions", o->directions,
                    "Number of horizon directions integrated (default: 16 with --quality auto, "
                    "64 with full)")
        ->check(finiteRange(4, 1024));
    addSearchOptions(cmd, o->search);
    cmd->callback([o, &ctx] { runAperture(*o, ctx); });
}

}  // namespace demlight::cli
