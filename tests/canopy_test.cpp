// Vegetation that lets light through (demlight/lighting/canopy.h, --canopy, --transmissivity): on an
// analytic scene, a box tree's shadow has the outline the sun's rays give and the value
// tau (tau cos on flat ground), a building's shadow stays dark, and the ground under the crown
// gets tau of what open ground gets; on real surface models, the limits tau = 1 (the ground and
// buildings alone) and tau = 0 (crowns as walls) and the bits of tiles.
#include "demlight/geo/dem.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/geo/time.h"
#include "demlight/lighting/canopy.h"
#include "demlight/products/insolation.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/light.h"
#include "demlight/products/point.h"
#include "demlight/products/sun.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "shared_dem.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace demlight {
namespace {

constexpr std::size_t kSide = 81;
constexpr double kTreeM = 10, kBuildingM = 8;
// Footprints in cells [col0, col1) x [row0, row1); cell c covers [c, c + 1).
constexpr double kTree[4] = {38, 43, 38, 43};
constexpr double kBuilding[4] = {60, 65, 20, 25};
constexpr double kTau = 0.2;

GeoReference sceneRef() {
    GeoReference ref;
    // UTM 10N's central meridian at 45 N: grid north is true north within 0.01 deg; 1 m cells.
    ref.geoTransform = {500000 - 40.5, 1, 0, 4982950 + 40.5, 0, -1};
    ref.crsWkt = "EPSG:32610";
    return ref;
}

bool inside(const double box[4], double col, double row) {
    return col >= box[0] && col < box[1] && row >= box[2] && row < box[3];
}

/// Flat ground at 0 m with the tree's crown and the building on it (the DSM), and the canopy.
struct Scene {
    Grid<float> dsm{kSide, kSide, 0.0f}, canopy{kSide, kSide, 0.0f}, ground{kSide, kSide, 0.0f};
    Scene() {
        for (std::size_t r = 0; r < kSide; ++r)
            for (std::size_t c = 0; c < kSide; ++c) {
                const double x = static_cast<double>(c) + 0.5, y = static_cast<double>(r) + 0.5;
                if (inside(kTree, x, y)) dsm(c, r) = canopy(c, r) = static_cast<float>(kTreeM);
                if (inside(kBuilding, x, y)) dsm(c, r) = ground(c, r) = static_cast<float>(kBuildingM);
            }
    }
};

enum class Shade { Open, Canopy, Building };

/// What the sun's ray from the point (col, row) (cell units, row southward) meets: the building
/// below its top, the tree below its top, or nothing (marched at 1 cm).
Shade rayShade(double col, double row, double azimuthDeg, double elevationDeg) {
    if (inside(kTree, col, row)) return Shade::Canopy;  // the ground under its own crown
    const double dc = std::sin(azimuthDeg * kDegToRad), dr = -std::cos(azimuthDeg * kDegToRad);
    const double rise = std::tan(elevationDeg * kDegToRad);
    Shade seen = Shade::Open;
    for (double t = 0; t < 60; t += 0.01) {
        const double c = col + dc * t, r = row + dr * t, z = rise * t;
        if (inside(kBuilding, c, r) && z < kBuildingM) return Shade::Building;
        if (inside(kTree, c, r) && z < kTreeM) seen = Shade::Canopy;
    }
    return seen;
}

/// The cell's shade where every point within 1.2 cells of its centre has the same (the bilinear
/// surface ramps over a cell at the boxes' edges); nullopt on the outlines.
std::optional<Shade> clearShade(std::size_t col, std::size_t row, double az, double el) {
    const double x = static_cast<double>(col) + 0.5, y = static_cast<double>(row) + 0.5;
    const Shade centre = rayShade(x, y, az, el);
    for (double dx : {-1.2, 0.0, 1.2})
        for (double dy : {-1.2, 0.0, 1.2})
            if (rayShade(x + dx, y + dy, az, el) != centre) return std::nullopt;
    return centre;
}

SunRequest morning(const std::string& canopyPath, double tau) {
    SunRequest r;
    r.time = parseZonedInstant("2024-06-21T08:30", "America/Los_Angeles");  // sun ESE, ~36 deg up
    r.canopy.raster = canopyPath;
    r.canopy.transmissivity = tau;
    r.search.threads = 2;
    return r;
}

TEST(Canopy, BoxTreeCastsTauShadowWithTheRaysOutlineAndTheBuildingStaysDark) {
    const Scene scene;
    const DemSource source(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    const SunResult r = sunProduct(source, source.whole(), morning(canopy.path(), kTau));
    const double az = r.centreAzimuthDeg, el = r.centreElevationDeg;
    ASSERT_GT(el, 25);
    ASSERT_LT(el, 50);
    const Grid<float>& vis = r.band("sun_visibility").values;
    const Grid<float>& irr = r.band("sun_irradiance").values;
    std::size_t counted[3] = {0, 0, 0};
    for (std::size_t row = 2; row + 2 < kSide; ++row)
        for (std::size_t col = 2; col + 2 < kSide; ++col) {
            const std::optional<Shade> shade = clearShade(col, row, az, el);
            if (!shade) continue;
            const double x = static_cast<double>(col) + 0.5, y = static_cast<double>(row) + 0.5;
            // Building cells are roofs (lit); around the building the ground's normals tilt.
            if (x > kBuilding[0] - 2 && x < kBuilding[1] + 2 && y > kBuilding[2] - 2 && y < kBuilding[3] + 2) continue;
            const double expected = *shade == Shade::Open ? 1.0 : *shade == Shade::Canopy ? kTau : 0.0;
            ++counted[static_cast<int>(*shade)];
            EXPECT_NEAR(vis(col, row), expected, 1e-3) << col << "," << row;
            // Flat ground: N.s = sin(elevation).
            EXPECT_NEAR(irr(col, row), expected * std::sin(el * kDegToRad), 2e-3) << col << "," << row;
        }
    // The scene has each kind, the tree's shadow (and the ground under it) a good patch.
    EXPECT_GT(counted[static_cast<int>(Shade::Open)], 3000u);
    EXPECT_GT(counted[static_cast<int>(Shade::Canopy)], 40u);
    EXPECT_GT(counted[static_cast<int>(Shade::Building)], 20u);
    EXPECT_EQ(r.metadata.at("DEMLIGHT_CANOPY"), canopy.path());
    EXPECT_EQ(r.metadata.at("DEMLIGHT_CANOPY_TRANSMISSIVITY"), "0.2");
}

TEST(Canopy, TransmissivityOneIsTheGroundAloneAndZeroMakesCrownsWalls) {
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const DemSource ground(demFromArray(scene.ground, sceneRef(), std::nullopt, "ground"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    const SunResult clear = sunProduct(dsm, dsm.whole(), morning(canopy.path(), 1.0));
    const SunResult bare = sunProduct(ground, ground.whole(), morning("", 0.03));
    const SunResult opaque = sunProduct(dsm, dsm.whole(), morning(canopy.path(), 0.0));
    const SunResult walls = sunProduct(dsm, dsm.whole(), morning("", 0.03));
    for (const char* band : {"sun_visibility", "sun_irradiance"}) {
        const Grid<float>& a = clear.band(band).values;
        const Grid<float>& b = bare.band(band).values;
        for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a.data()[k], b.data()[k], 1e-6) << band << " " << k;
    }
    // tau = 0: the DSM's shadows, but the ground under the crown is dark (its crown's top is lit).
    const Grid<float>& o = opaque.band("sun_visibility").values;
    const Grid<float>& w = walls.band("sun_visibility").values;
    for (std::size_t r = 0; r < kSide; ++r)
        for (std::size_t c = 0; c < kSide; ++c) {
            const double x = static_cast<double>(c) + 0.5, y = static_cast<double>(r) + 0.5;
            if (inside(kTree, x, y)) {
                EXPECT_EQ(o(c, r), 0.0f) << c << "," << r;
                // The crown's flat top (its edge cells slope as steeply as a wall on the bilinear surface).
                if (inside(kTree, x - 1, y - 1) && inside(kTree, x + 1, y + 1)) {
                    EXPECT_GT(w(c, r), 0.99f) << c << "," << r;
                }
            } else if (!(x > kTree[0] - 1.5 && x < kTree[1] + 1.5 && y > kTree[2] - 1.5 && y < kTree[3] + 1.5)) {
                EXPECT_NEAR(o(c, r), w(c, r), 1e-6) << c << "," << r;  // beside the crown the normals differ
            }
        }
}

// Under the crown every quantity is tau of the ground's without the tree, plus (1 - tau) of
// everything hidden: no beam, no sky, the reflected light of the whole view.
TEST(Canopy, GroundUnderTheCrownGetsTauOfOpenGroundInIrradianceAndInsolation) {
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const DemSource ground(demFromArray(scene.ground, sceneRef(), std::nullopt, "ground"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    const std::size_t col = 40, row = 40;

    IrradianceRequest irr;
    irr.time = parseZonedInstant("2024-06-21T12:00", "America/Los_Angeles");
    irr.search.threads = 2;
    irr.search.maxDistanceM = 60;
    IrradianceRequest withCanopy = irr;
    withCanopy.canopy = {canopy.path(), kTau};
    const IrradianceResult a = irradianceProduct(dsm, dsm.whole(), withCanopy);
    const IrradianceResult b = irradianceProduct(ground, ground.whole(), irr);
    EXPECT_NEAR(a.band("beam").values(col, row), kTau * b.band("beam").values(col, row), 1e-3);
    EXPECT_NEAR(a.band("diffuse").values(col, row), kTau * b.band("diffuse").values(col, row), 1e-3);
    EXPECT_GT(b.band("beam").values(col, row), 500.0f);

    InsolationRequest ins;
    ins.zone = TimeZoneSpec::iana("America/Los_Angeles");
    ins.firstDay = ins.lastDay = std::chrono::sys_days{std::chrono::year{2024} / 6 / 21};
    ins.search.threads = 2;
    ins.search.maxDistanceM = 60;
    ins.directions = 16;
    InsolationRequest insCanopy = ins;
    insCanopy.canopy = {canopy.path(), kTau};
    const InsolationResult c = insolationProduct(dsm, dsm.whole(), insCanopy);
    const InsolationResult d = insolationProduct(ground, ground.whole(), ins);
    for (const char* band : {"beam", "diffuse", "sun_hours"})
        EXPECT_NEAR(c.band(band).values(col, row), kTau * d.band(band).values(col, row),
                    1e-4 * std::max(1.0f, d.band(band).values(col, row)))
            << band;
    EXPECT_GT(d.band("sun_hours").values(col, row), 10.0f);
}

// Sun hours: the ground under the crown gets tau of the ground's sun hours and sun irradiation
// without the tree, and tau = 1 gives the ground alone.
TEST(Canopy, SunhoursUnderTheCrownAreTauOfOpenGround) {
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const DemSource ground(demFromArray(scene.ground, sceneRef(), std::nullopt, "ground"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    SunhoursRequest r;
    r.zone = TimeZoneSpec::iana("America/Los_Angeles");
    r.firstDay = r.lastDay = std::chrono::sys_days{std::chrono::year{2024} / 6 / 21};
    r.step = std::chrono::minutes(30);
    r.search.threads = 2;
    r.search.maxDistanceM = 60;
    SunhoursRequest withCanopy = r;
    withCanopy.canopy = {canopy.path(), kTau};
    const SunhoursResult a = sunhoursProduct(dsm, dsm.whole(), withCanopy);
    const SunhoursResult b = sunhoursProduct(ground, ground.whole(), r);
    for (const char* band : {"sun_hours", "sun_irradiation"})
        EXPECT_NEAR(a.band(band).values(40, 40), kTau * b.band(band).values(40, 40),
                    1e-4 * b.band(band).values(40, 40))
            << band;
    EXPECT_GT(b.band("sun_hours").values(40, 40), 12.0f);
    EXPECT_EQ(a.band("first_lit").values(40, 40), kNeverLitClock);  // tau < the lit threshold
    withCanopy.canopy.transmissivity = 1;
    const SunhoursResult clear = sunhoursProduct(dsm, dsm.whole(), withCanopy);
    for (const char* band : {"sun_hours", "sun_irradiation", "sky_irradiation"}) {
        const Grid<float>& x = clear.band(band).values;
        const Grid<float>& y = b.band(band).values;
        for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x.data()[k], y.data()[k], 1e-5) << band << " " << k;
    }
    SunhoursRequest stacked = withCanopy;
    stacked.stackDirections = 64;
    EXPECT_THROW(sunhoursProduct(dsm, dsm.whole(), stacked), FieldError);
}

// light: tau = 1 is the ground and buildings alone (sun and sky); under the crown, with albedo 0
// (no interreflection, so the sky term is K itself), tau of open ground's light; the sun term
// alone is the sun product's irradiance under the same canopy.
TEST(Canopy, LightUnderTheCrownIsTauOfOpenGroundAndTauOneIsTheGroundAlone) {
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const DemSource ground(demFromArray(scene.ground, sceneRef(), std::nullopt, "ground"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    LightRequest r;
    r.time = parseZonedInstant("2024-06-21T12:00", "America/Los_Angeles");
    r.search.threads = 2;
    r.search.maxDistanceM = 60;
    r.skyDirections = 16;
    const Grid<float> bare = lightProduct(ground, ground.whole(), r).band("light").values;
    LightRequest clear = r;
    clear.canopy = {canopy.path(), 1.0};
    const LightResult a = lightProduct(dsm, dsm.whole(), clear);
    const Grid<float>& x = a.band("light").values;
    for (std::size_t k = 0; k < x.size(); ++k) EXPECT_NEAR(x.data()[k], bare.data()[k], 1e-5) << k;
    EXPECT_EQ(a.metadata.at("DEMLIGHT_CANOPY"), canopy.path());

    LightRequest dark = r;
    dark.albedo = 0.0;
    const Grid<float> open = lightProduct(ground, ground.whole(), dark).band("light").values;
    dark.canopy = {canopy.path(), kTau};
    const Grid<float> under = lightProduct(dsm, dsm.whole(), dark).band("light").values;
    EXPECT_GT(open(40, 40), 1.0f);  // a noon sun and the open sky
    EXPECT_NEAR(under(40, 40), kTau * open(40, 40), 1e-4);

    LightRequest sunOnly = r;
    sunOnly.skyModel = SkyModel::None;
    sunOnly.canopy = {canopy.path(), kTau};
    const Grid<float> light = lightProduct(dsm, dsm.whole(), sunOnly).band("light").values;
    SunRequest sun;
    sun.time = r.time;
    sun.search = r.search;
    sun.canopy = sunOnly.canopy;
    const Grid<float> irradiance = sunProduct(dsm, dsm.whole(), sun).band("sun_irradiance").values;
    for (std::size_t k = 0; k < light.size(); ++k) EXPECT_FLOAT_EQ(light.data()[k], irradiance.data()[k]) << k;

    LightRequest hemisphere = sunOnly;
    hemisphere.skyModel = SkyModel::Hemisphere;
    EXPECT_THROW(lightProduct(dsm, dsm.whole(), hemisphere), FieldError);
    LightRequest aperture = sunOnly;
    aperture.model = SunModel::Aperture;
    EXPECT_THROW(lightProduct(dsm, dsm.whole(), aperture), FieldError);
}

// timelapse: each frame is the sun product under the same canopy at its instant, and with
// tau = 1 the sky term is the ground's alone; interpolated horizons refuse a canopy.
TEST(Canopy, TimelapseFramesAreTheSunProductsAndTauOneSkyIsTheGroundsAlone) {
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    const DemSource ground(demFromArray(scene.ground, sceneRef(), std::nullopt, "ground"));
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    const ZonedInstant t0 = parseZonedInstant("2024-06-21T08:30", "America/Los_Angeles");
    TimelapseRequest r;
    r.frames = instantsBetween(t0, parseZonedInstant("2024-06-21T10:30", "America/Los_Angeles"),
                               std::chrono::hours(1), 10);
    r.previews = false;
    r.search.threads = 2;
    r.search.maxDistanceM = 60;
    r.skyDirections = 16;
    const auto run = [&](const DemSource& dem, const TimelapseRequest& request) {
        std::vector<ProductResult> frames;
        Grid<float> skyK;
        TimelapseSink sink;
        sink.sky = [&](ProductResult&& s) { skyK = s.bands.at(0).values; };
        sink.frame = [&](TimelapseFrame&& f) { frames.push_back(std::move(f.lightmap)); };
        timelapseProduct(dem, dem.whole(), request, sink);
        return std::pair(std::move(frames), std::move(skyK));
    };
    TimelapseRequest withCanopy = r;
    withCanopy.canopy = {canopy.path(), kTau};
    const auto [frames, skyK] = run(dsm, withCanopy);
    ASSERT_EQ(frames.size(), 3u);
    for (std::size_t i = 0; i < frames.size(); ++i) {
        SunRequest sun;
        sun.time = {r.frames.instants[i], r.frames.zone};
        sun.search = r.search;
        sun.canopy = withCanopy.canopy;
        const SunResult expected = sunProduct(dsm, dsm.whole(), sun);
        for (const char* band : {"sun_visibility", "sun_irradiance"}) {
            const Grid<float>& a = frames[i].band(band).values;
            const Grid<float>& b = expected.band(band).values;
            for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a.data()[k], b.data()[k]) << i << " " << band << " " << k;
        }
        EXPECT_EQ(frames[i].metadata.at("DEMLIGHT_CANOPY"), canopy.path());
    }
    EXPECT_NEAR(frames[0].band("sun_visibility").values(40, 40), 0.0, 1e-6 + kTau);  // under the crown

    withCanopy.canopy.transmissivity = 1;
    const Grid<float> clearSky = run(dsm, withCanopy).second;
    const Grid<float> bareSky = run(ground, r).second;
    for (std::size_t k = 0; k < clearSky.size(); ++k) EXPECT_NEAR(clearSky.data()[k], bareSky.data()[k], 1e-6) << k;
    // Under the crown with tau = 0.2 the sky is tau of the open ground's.
    EXPECT_NEAR(skyK(40, 40), kTau * bareSky(40, 40), 1e-5);

    withCanopy.stackDirections = 64;
    EXPECT_THROW(timelapseProduct(dsm, dsm.whole(), withCanopy, TimelapseSink{}), FieldError);
}

TEST(Canopy, OutOfRangeValuesAndPointQueriesAreRefused) {
    SunRequest r = morning("", 1.5);
    r.canopy.raster = "x.tif";
    const Scene scene;
    const DemSource dsm(demFromArray(scene.dsm, sceneRef(), std::nullopt, "box tree"));
    EXPECT_THROW(sunProduct(dsm, dsm.whole(), r), FieldError);
    Grid<float> tall = scene.canopy;
    tall(3, 3) = 400;
    const MemoryRaster bad(tall, sceneRef(), std::nullopt);
    try {
        sunProduct(dsm, dsm.whole(), morning(bad.path(), 0.03));
        ADD_FAILURE() << "a 400 m tree was accepted";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "canopyRaster");
    }
    // Point queries march one surface: a canopy is refused, not ignored.
    IrradianceRequest irr;
    irr.time = parseZonedInstant("2024-06-21T12:00", "America/Los_Angeles");
    const MemoryRaster canopy(scene.canopy, sceneRef(), std::nullopt);
    irr.canopy = {canopy.path(), 0.03};
    const PointCell p = locatePoint(dsm, {500000, 4982950, false});
    try {
        pointIrradiance(dsm, p, irr);
        ADD_FAILURE() << "a point query ignored the canopy";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "canopy");
    }
}

/// A canopy made from a surface model: its height above the lowest cell within 3 cells where that
/// is 2-40 m (trees, and roof edges too: the limits below hold for any canopy).
Grid<float> canopyFrom(const Grid<float>& dsm) {
    Grid<float> out(dsm.width(), dsm.height(), 0.0f);
    for (std::size_t r = 0; r < dsm.height(); ++r)
        for (std::size_t c = 0; c < dsm.width(); ++c) {
            if (std::isnan(dsm(c, r))) continue;
            float low = dsm(c, r);
            for (std::size_t rr = r >= 3 ? r - 3 : 0; rr <= std::min(dsm.height() - 1, r + 3); ++rr)
                for (std::size_t cc = c >= 3 ? c - 3 : 0; cc <= std::min(dsm.width() - 1, c + 3); ++cc)
                    if (!std::isnan(dsm(cc, rr))) low = std::min(low, dsm(cc, rr));
            const float above = dsm(c, r) - low;
            if (above >= 2 && above <= 40) out(c, r) = above;
        }
    return out;
}

class CanopyOnDsm : public ::testing::TestWithParam<const char*> {};

// On a real surface model: tau = 1 is the ground-and-buildings surface without a canopy; every
// cell's visibility lies between tau = 0's and tau = 1's; and a window (a tile with its halo)
// gives the whole DEM's bits.
TEST_P(CanopyOnDsm, LimitsAndTilesHold) {
    const std::string path = sharedDemPath(std::string("../dsm/") + GetParam());
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared surface model not found: " << GetParam();
    const DemSource dsm = DemSource::open(path);
    const std::shared_ptr<const Dem> whole = dsm.readWhole();
    const Grid<float> canopyGrid = canopyFrom(whole->terrain.heightsM);
    const MemoryRaster canopy(canopyGrid, whole->band.ref, std::nullopt);
    const CanopyGround g = canopyGround(whole->terrain.heightsM, canopyGrid);
    const DemSource ground(demFromArray(g.groundM, whole->band.ref, std::nullopt, "ground"));

    SunRequest r = morning(canopy.path(), 1.0);
    r.search.maxDistanceM = 150;
    const SunResult clear = sunProduct(dsm, dsm.whole(), r);
    SunRequest plain = r;
    plain.canopy = {};
    const SunResult bare = sunProduct(ground, ground.whole(), plain);
    r.canopy.transmissivity = 0;
    const SunResult opaque = sunProduct(dsm, dsm.whole(), r);
    r.canopy.transmissivity = kDefaultCanopyTransmissivity;
    const SunResult leafy = sunProduct(dsm, dsm.whole(), r);
    const Grid<float>& c = clear.band("sun_visibility").values;
    const Grid<float>& b = bare.band("sun_visibility").values;
    const Grid<float>& o = opaque.band("sun_visibility").values;
    const Grid<float>& l = leafy.band("sun_visibility").values;
    std::size_t differ = 0, outside = 0, filtered = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
        if (std::isnan(b.data()[k])) continue;
        differ += std::abs(c.data()[k] - b.data()[k]) > 1e-6f;
        outside += l.data()[k] < std::min(o.data()[k], c.data()[k]) - 1e-6f ||
                   l.data()[k] > std::max(o.data()[k], c.data()[k]) + 1e-6f;
        filtered += o.data()[k] < c.data()[k] - 0.5f;
    }
    EXPECT_EQ(differ, 0u);
    EXPECT_EQ(outside, 0u);
    EXPECT_GT(filtered, c.size() / 50) << "the canopy shades a share of the cells";

    const CellWindow w{dsm.width() / 3, dsm.height() / 4, dsm.width() / 3 + 120, dsm.height() / 4 + 90};
    const SunResult part = sunProduct(dsm, w, r);
    const Grid<float> expected = cropGrid(l, w);
    const Grid<float>& got = part.band("sun_visibility").values;
    EXPECT_EQ(std::memcmp(expected.data(), got.data(), expected.size() * sizeof(float)), 0);

    // light's sun and sky under the canopy: the window's bits too.
    LightRequest light;
    light.time = r.time;
    light.search = r.search;
    light.canopy = r.canopy;
    light.skyDirections = 8;
    const Grid<float> wholeLight = lightProduct(dsm, dsm.whole(), light).band("light").values;
    const Grid<float> partLight = lightProduct(dsm, w, light).band("light").values;
    const Grid<float> expectedLight = cropGrid(wholeLight, w);
    EXPECT_EQ(std::memcmp(expectedLight.data(), partLight.data(), expectedLight.size() * sizeof(float)), 0);
}

INSTANTIATE_TEST_SUITE_P(SharedDems, CanopyOnDsm,
                         ::testing::Values("nyc_ccny_harlem_1m_dsm.tif", "ahn_monster_westland_nl_0p5m_dsm.tif"),
                         [](const auto& testInfo) { return demTestName(testInfo.param); });

}  // namespace
}  // namespace demlight
