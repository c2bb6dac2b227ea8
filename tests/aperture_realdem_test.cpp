// Aperture vs horizon sun visibility over one day on a real DEM (docs/design.md §6.4: the
// aperture's known failure is band-shaped visibility, N-S canyons, that no single cap fits).
//
// Every 30 minutes of a local day with the sun up at the DEM centre, each valid cell is
// classified lit (visibility >= 0.5) or in shadow by the horizon model (computeSunFrame, the
// `demlight sun` default) and by the aperture models (applyApertureSun with the aperture from
// kDefaultSkyDirections sweeps, `demlight sun --model aperture|aperture-smooth`). The table gives
// the share of cell-instants on which they disagree, split by the aperture radius r_p and by
// the horizon asymmetry a = mean(h_E, h_W) - mean(h_N, h_S) (horizons clipped at 0): a > 0 is
// a trough running north-south, whose visible sky is a N-S band that no cap centred on one
// bent normal can represent. The same asymmetry taken relative to the sun's azimuth at each
// instant, a_sun = mean(h at sun az +- 90) - mean(h at sun az, sun az + 180), says whether the
// band runs towards the sun (a_sun > 10: the sun shines along the trough, which the cap, narrowed
// by the side walls, misses: false shadow) or across it (a_sun < -10: walls towards and away
// from the sun, which the cap, widened along the open axis, ignores: false lit).
#include "demlight/geo/dem.h"
#include "demlight/geo/sun_field.h"
#include "demlight/geo/time.h"
#include "demlight/lighting/aperture.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/lighting_models.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/surface.h"

#include "shared_dem.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace demlight {
namespace {

constexpr double kLitThreshold = 0.5;
/// Asymmetry (degrees) beyond which a cell counts as a N-S or E-W trough.
constexpr double kTroughAsymmetryDeg = 10.0;


/// Tallies of one class of cells.
struct Tally {
    double cells = 0, wrongExact = 0, wrongSmooth = 0, falseLit = 0, falseShadow = 0;
    void add(bool litH, bool litA, bool litS) {
        cells += 1;
        wrongExact += litH != litA;
        wrongSmooth += litH != litS;
        falseLit += litA && !litH;
        falseShadow += !litA && litH;
    }
};

struct Day {
    std::string file;
    std::string date;  ///< local date
    std::string tz;
    /// Runs only with DEMLIGHT_LONG_TESTS set (keeps the default suite short).
    bool longRun = false;
};

void PrintTo(const Day& d, std::ostream* os) { *os << d.file << " " << d.date; }

/// applyApertureSun on open flat ground: the sun is fully covered above the horizon (the
/// aperture is the whole hemisphere), half covered on it, and the direct term is sin(elevation).
TEST(ApertureSun, FlatGroundMatchesHorizonModel) {
    const Terrain t = makeUniformTerrain(Grid<float>(16, 16, 100.0f), 30.0);
    const Normals normals = computeNormals(t);
    ApertureAccumulator acc(normals.east, normals.north, normals.up, kDefaultSkyDirections);
    HorizonParams hp;
    hp.maxDistanceM = 1000.0;
    sweepDirections(t, hp, kDefaultSkyDirections, [&](std::size_t i, const HorizonMap& m) { acc.addDirection(i, m.angleDeg); });
    const ApertureMaps ap = acc.finish();
    for (const bool smooth : {false, true}) {
        ApertureLightParams lp;
        lp.smoothIntersection = smooth;
        for (const double el : {0.0, 5.0, 30.0, 89.0}) {
            const ApertureSunMaps m = applyApertureSun(ap, normals.east, normals.north, normals.up,
                                                       SunField::uniform(123.0, el), lp);
            const double vis = el == 0.0 ? 0.5 : 1.0;
            EXPECT_NEAR(m.visibility(8, 8), vis, 1e-6) << "elevation " << el << " smooth " << smooth;
            EXPECT_NEAR(m.irradiance(8, 8), vis * std::sin(el * std::numbers::pi / 180.0), 2e-3)
                << "elevation " << el << " smooth " << smooth;
        }
    }
}

class ApertureVsHorizon : public ::testing::TestWithParam<Day> {};

TEST_P(ApertureVsHorizon, SunVisibilityOverOneDay) {
    const Day& day = GetParam();
    const std::string path = sharedDemPath(day.file);
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared DEM not found: " << path;
    if (day.longRun && !std::getenv("DEMLIGHT_LONG_TESTS"))
        GTEST_SKIP() << "long run; set DEMLIGHT_LONG_TESTS=1 to run it";
    const Dem dem = loadDem(path);
    const Terrain& t = dem.terrain;
    const Normals normals = computeNormals(t);

    // Aperture once, as `demlight sun --model aperture` does; keep every direction's horizons.
    HorizonParams hp;
    hp.maxDistanceM = defaultMaxDistanceM(t);
    const std::size_t d = kDefaultSkyDirections;
    ApertureAccumulator acc(normals.east, normals.north, normals.up, d);
    std::vector<Grid<float>> horizons;  // direction i at azimuth i * 360 / d
    sweepDirections(t, hp, d, [&](std::size_t i, const HorizonMap& m) {
        acc.addDirection(i, m.angleDeg);
        horizons.push_back(m.angleDeg);
    });
    /// Horizon (clipped at 0) of a cell in the sector nearest to azimuthDeg.
    const auto horizonAt = [&](std::size_t col, std::size_t row, double azimuthDeg) {
        const double sector = std::round(azimuthDeg / (360.0 / static_cast<double>(d)));
        const auto i = static_cast<std::size_t>(std::fmod(std::fmod(sector, static_cast<double>(d)) + static_cast<double>(d),
                                                          static_cast<double>(d)));
        return std::max(0.0, static_cast<double>(horizons[i](col, row)));
    };
    const ApertureMaps ap = acc.finish();

    // Classes: radius bins, then asymmetry bins.
    const std::array<double, 5> radiusEdges = {45, 60, 75, 85, 90.01};
    const std::array<const char*, 5> radiusNames = {"r_p < 45", "45..60", "60..75", "75..85", ">= 85"};
    const std::array<const char*, 3> asymNames = {"N-S trough (a > 10)", "E-W trough (a < -10)", "|a| <= 10"};
    const std::array<const char*, 3> sunNames = {"along sun (a_sun > 10)", "across sun (a_sun<-10)", "|a_sun| <= 10"};
    std::array<Tally, 5> byRadius{};
    std::array<Tally, 3> byAsym{}, bySun{};
    Tally all;

    const ZonedInstant start = parseZonedInstant(day.date + "T00:00:00", day.tz);
    SolarSite site;
    ApertureLightParams exact, smooth;
    smooth.smoothIntersection = true;
    SunFrameParams sp;
    int instants = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int step = 0; step < 48; ++step) {
        const UtcInstant when = start.utc + std::chrono::minutes(30 * step);
        const SunField field = computeSunField(dem, when, site, SpaOptions{});
        if (field.centreElevationDeg <= 0.0) continue;
        ++instants;
        const SunFrame h = computeSunFrame(t, normals, field, sp);
        const ApertureSunMaps a = applyApertureSun(ap, normals.east, normals.north, normals.up, field, exact);
        const ApertureSunMaps s = applyApertureSun(ap, normals.east, normals.north, normals.up, field, smooth);
        for (std::size_t row = 0; row < t.height(); ++row)
            for (std::size_t col = 0; col < t.width(); ++col) {
                const float vh = h.light.visibility(col, row), va = a.visibility(col, row);
                if (std::isnan(vh) || std::isnan(va)) continue;
                const bool litH = vh >= kLitThreshold, litA = va >= kLitThreshold,
                           litS = s.visibility(col, row) >= kLitThreshold;
                all.add(litH, litA, litS);
                const double r = ap.radiusDeg(col, row);
                const auto rb = static_cast<std::size_t>(
                    std::upper_bound(radiusEdges.begin(), radiusEdges.end(), r) - radiusEdges.begin());
                byRadius[std::min<std::size_t>(rb, 4)].add(litH, litA, litS);
                const auto trough = [&](double azDeg) {
                    return 0.5 * (horizonAt(col, row, azDeg + 90.0) + horizonAt(col, row, azDeg + 270.0)) -
                           0.5 * (horizonAt(col, row, azDeg) + horizonAt(col, row, azDeg + 180.0));
                };
                const auto bin = [](double asym) {
                    return asym > kTroughAsymmetryDeg ? 0u : asym < -kTroughAsymmetryDeg ? 1u : 2u;
                };
                byAsym[bin(trough(0.0))].add(litH, litA, litS);
                bySun[bin(trough(field.at(static_cast<double>(col) + 0.5, static_cast<double>(row) + 0.5).first))]
                    .add(litH, litA, litS);
            }
    }
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_GT(instants, 10);

    char line[512];
    std::snprintf(line, sizeof line,
                  "%s, %s (%s), %d half-hour instants with the sun up, %zu x %zu cells, D = %zu, %.1f s\n",
                  day.file.c_str(), day.date.c_str(), day.tz.c_str(), instants, t.width(), t.height(), d, secs);
    std::cout << line;
    const auto row = [&](const char* name, const Tally& x) {
        std::snprintf(line, sizeof line,
                      "  %-22s share %6.2f %% | misclassified: aperture %6.2f %% (false lit %5.2f %%, "
                      "false shadow %5.2f %%), smooth %6.2f %% | share of all errors %5.1f %%\n",
                      name, 100.0 * x.cells / all.cells, 100.0 * x.wrongExact / std::max(1.0, x.cells),
                      100.0 * x.falseLit / std::max(1.0, x.cells), 100.0 * x.falseShadow / std::max(1.0, x.cells),
                      100.0 * x.wrongSmooth / std::max(1.0, x.cells), 100.0 * x.wrongExact / std::max(1.0, all.wrongExact));
        std::cout << line;
        RecordProperty(day.file + " " + name, line);
    };
    row("all cells", all);
    for (std::size_t i = 0; i < byRadius.size(); ++i) row(radiusNames[i], byRadius[i]);
    for (std::size_t i = 0; i < byAsym.size(); ++i) row(asymNames[i], byAsym[i]);
    for (std::size_t i = 0; i < bySun.size(); ++i) row(sunNames[i], bySun[i]);

    // Loose bounds (README "Sky accuracy" has the measured numbers): the aperture model is a
    // one-cap summary, right for most open cells but not a shadow method.
    EXPECT_LT(all.wrongExact / all.cells, 0.25);
    EXPECT_LT(byRadius[4].wrongExact / std::max(1.0, byRadius[4].cells), all.wrongExact / all.cells + 1e-9)
        << "nearly open cells should be classified at least as well as the average";
    // The named failure: troughs along the sun are band-shaped visibility the cap misses (false
    // shadow), troughs across the sun hide a sun the cap contains (false lit). Measured: 1.5-2.4
    // times the overall rate, almost all of one sign.
    const double overall = all.wrongExact / all.cells;
    EXPECT_GT(bySun[0].wrongExact / bySun[0].cells, 1.5 * overall);
    EXPECT_GT(bySun[0].falseShadow, 10.0 * bySun[0].falseLit);
    EXPECT_GT(bySun[1].wrongExact / bySun[1].cells, 1.5 * overall);
    EXPECT_GT(bySun[1].falseLit, 10.0 * bySun[1].falseShadow);
}

INSTANTIATE_TEST_SUITE_P(SharedDems, ApertureVsHorizon,
                         ::testing::Values(Day{"big_tujunga_srtm30m_utm11.tif", "2024-12-21", "America/Los_Angeles"},
                                           Day{"big_tujunga_srtm30m_utm11.tif", "2024-06-21", "America/Los_Angeles", true}),
                         [](const ::testing::TestParamInfo<Day>& param) {
                             std::string name = param.param.file.substr(0, param.param.file.find('.')) + "_" +
                                                param.param.date;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

}  // namespace
}  // namespace demlight
