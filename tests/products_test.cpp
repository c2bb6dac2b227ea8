// The products layer called directly, without the CLI: bands, georeference, metadata, progress
// and cancellation, windows, the light combination, and library messages in library terms.
#include "demlight/core/parallel.h"
#include "demlight/geo/dem_source.h"
#include "demlight/geo/raster.h"
#include "demlight/geo/time.h"
#include "demlight/products/aperture.h"
#include "demlight/products/horizon.h"
#include "demlight/products/info.h"
#include "demlight/products/light.h"
#include "demlight/products/render.h"
#include "demlight/products/sequence.h"
#include "demlight/products/sky.h"
#include "demlight/products/sun.h"
#include "demlight/products/sunhours.h"
#include "demlight/products/timelapse.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>
#include <string>
#include <vector>

namespace demlight {
namespace {

const std::string kRocky = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
const std::string kHelens = std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem";

const DemSource& rocky() {
    static const DemSource source = DemSource::open(kRocky);
    return source;
}

ZonedInstant morning() { return parseZonedInstant("2024-06-21T14:30:00Z", ""); }

std::vector<std::string> names(const ProductResult& r) {
    std::vector<std::string> out;
    for (const auto& b : r.bands) out.push_back(b.name);
    return out;
}

TEST(Products, EveryRasterProductKeepsTheDemGeoreferenceAndNamesItsBands) {
    const DemSource& dem = rocky();
    SearchRequest search;
    search.threads = 2;
    HorizonRequest h;
    h.azimuthsDeg = {0, 135};
    h.search = search;
    const HorizonResult hr = horizonProduct(dem, dem.whole(), h);
    EXPECT_EQ(names(hr.horizons), (std::vector<std::string>{"horizon_azimuth=0", "horizon_azimuth=135"}));
    EXPECT_EQ(names(hr.truncation), (std::vector<std::string>{"truncated_azimuth=0", "truncated_azimuth=135"}));
    EXPECT_EQ(hr.truncation.flagNodata, 255.0);

    SkyRequest sky;
    sky.search = search;
    const SkyResult sr = skyProduct(dem, dem.whole(), sky);
    EXPECT_EQ(names(sr), (std::vector<std::string>{"svf_horizontal", "sky_fraction", "sky_K", "sky_factor"}));

    SunRequest sun;
    sun.time = morning();
    sun.search = search;
    const SunResult su = sunProduct(dem, dem.whole(), sun);
    EXPECT_EQ(names(su), (std::vector<std::string>{"sun_visibility", "sun_irradiance"}));
    EXPECT_TRUE(su.sunUp);

    ApertureRequest ap;
    ap.search = search;
    EXPECT_EQ(apertureProduct(dem, dem.whole(), ap).bands.size(), 5u);

    for (const ProductResult* r : std::initializer_list<const ProductResult*>{&hr.horizons, &sr, &su}) {
        EXPECT_EQ(r->ref.geoTransform, dem.geometry().band.ref.geoTransform);
        EXPECT_EQ(r->ref.crsWkt, dem.geometry().band.ref.crsWkt);
        EXPECT_EQ(r->metadata.at("DEMLIGHT_INPUT"), kRocky);
        for (const auto& b : r->bands) {
            EXPECT_EQ(b.values.width(), dem.width()) << b.name;
            EXPECT_EQ(b.values.height(), dem.height()) << b.name;
        }
    }
    EXPECT_EQ(su.metadata.at("DEMLIGHT_PRODUCT"), "sun");
    EXPECT_EQ(su.metadata.at("DEMLIGHT_REFRACTION"), "0.13");
}

TEST(Products, EveryProductRunsOnTheThreadsItsRequestAsksFor) {
    // A product call enters its request's thread count once (no kernel takes one): its work, and
    // so its progress reports, run on that many threads; 0 = every core.
    if (resolveThreadCount(0) < 2) GTEST_SKIP() << "needs two cores";
    const DemSource& dem = rocky();
    const CellWindow w = dem.whole();
    for (const int threads : {1, 0}) {
        std::vector<int> seen;
        const ProgressFn progress = [&](double, const std::string&) {
            seen.push_back(runThreads());
            return true;
        };
        SearchRequest search;
        search.threads = threads;
        search.maxDistanceM = 3000;
        HorizonRequest h;
        h.azimuthsDeg = {10, 200};
        h.search = search;
        horizonProduct(dem, w, h, progress);
        SunRequest sun;
        sun.time = morning();
        sun.search = search;
        sunProduct(dem, w, sun, progress);
        SkyRequest sky;
        sky.directions = 8;
        sky.search = search;
        skyProduct(dem, w, sky, progress);
        ApertureRequest aperture;
        aperture.directions = 8;
        aperture.search = search;
        apertureProduct(dem, w, aperture, progress);
        SunhoursRequest hours;
        hours.firstDay = hours.lastDay = parseDate("2024-06-21");
        hours.step = std::chrono::minutes(120);
        hours.search = search;
        sunhoursProduct(dem, w, hours, progress);
        ASSERT_FALSE(seen.empty());
        const int expected = threads == 1 ? 1 : runThreads();
        for (int n : seen) EXPECT_EQ(n, expected) << "threads " << threads;
    }
}

TEST(Products, ProgressIsSizedByTheProductAndReachesOne) {
    const DemSource& dem = rocky();
    SunhoursRequest r;
    r.firstDay = r.lastDay = parseDate("2024-06-21");
    r.step = std::chrono::minutes(60);
    r.search.threads = 2;
    std::vector<std::pair<std::string, double>> calls;
    const ProgressFn progress = [&](double f, const std::string& stage) {
        calls.emplace_back(stage, f);
        return true;
    };
    sunhoursProduct(dem, dem.whole(), r, progress);
    ASSERT_FALSE(calls.empty());
    double last = -1;
    std::string stage;
    bool reachedOne = false;
    for (const auto& [s, f] : calls) {
        if (s != stage) stage = s, last = -1;
        EXPECT_GE(f, last) << s;
        EXPECT_LE(f, 1.0);
        last = f;
        reachedOne = reachedOne || (s == "sunhours" && f == 1.0);
    }
    EXPECT_TRUE(reachedOne);
}

TEST(Products, ACallbackThatReturnsFalseCancels) {
    const DemSource& dem = rocky();
    SkyRequest r;
    r.search.threads = 2;
    int calls = 0;
    const ProgressFn stop = [&](double, const std::string&) { return ++calls < 3; };
    EXPECT_THROW(skyProduct(dem, dem.whole(), r, stop), Cancelled);
}

TEST(Products, LightIsSunIrradianceTimesCloudPlusSkyFactor) {
    // combineLight, cell by cell: reflectance x (sunColour x sun x cloud + skyColour x sky).
    Grid<float> h(3, 1, 100.0f), sun(3, 1), cloud(3, 1), sky(3, 1), red(3, 1, 0.5f), green(3, 1, 0.25f), blue(3, 1, 1.0f);
    h(2, 0) = std::nanf("");
    sun(0, 0) = 0.8f, sun(1, 0) = 0.2f;
    cloud(0, 0) = 0.5f, cloud(1, 0) = std::nanf("");  // NaN cloud leaves the sun as it is
    sky(0, 0) = 0.9f, sky(1, 0) = 0.4f;
    LightTerms terms;
    terms.heightsM = &h;
    terms.sunIrradiance = &sun;
    terms.cloud = &cloud;
    terms.sky = {&sky};
    terms.reflectance = {&red, &green, &blue};
    terms.sunColor = {1.0, 2.0, 0.5};
    terms.skyColor = {0.1, 0.2, 0.3};
    terms.channels = 3;
    const auto light = combineLight(terms);
    ASSERT_EQ(light.size(), 3u);
    EXPECT_NEAR(light[0](0, 0), 0.5 * (1.0 * 0.8 * 0.5 + 0.1 * 0.9), 1e-6);
    EXPECT_NEAR(light[1](0, 0), 0.25 * (2.0 * 0.8 * 0.5 + 0.2 * 0.9), 1e-6);
    EXPECT_NEAR(light[2](1, 0), 1.0 * (0.5 * 0.2 + 0.3 * 0.4), 1e-6);
    EXPECT_TRUE(std::isnan(light[0](2, 0)));

    // The light product against the sun and sky products of the same plan: light = sun_irradiance
    // + sky_factor on every cell (both at the plan's default directions and albedo).
    const DemSource& dem = rocky();
    SearchRequest search;
    search.threads = 2;
    LightRequest lr;
    lr.time = morning();
    lr.search = search;
    const LightResult l = lightProduct(dem, dem.whole(), lr);
    SunRequest sr;
    sr.time = morning();
    sr.search = search;
    SkyRequest kr;
    kr.search = search;
    const SunResult s = sunProduct(dem, dem.whole(), sr);
    const SkyResult k = skyProduct(dem, dem.whole(), kr);
    const Grid<float>& lg = l.band("light").values;
    const Grid<float>& sg = s.band("sun_irradiance").values;
    const Grid<float>& kg = k.band("sky_factor").values;
    std::size_t checked = 0;
    for (std::size_t i = 0; i < lg.size(); ++i) {
        if (std::isnan(lg.data()[i])) continue;
        EXPECT_NEAR(lg.data()[i], sg.data()[i] + kg.data()[i], 1e-6);
        ++checked;
    }
    EXPECT_EQ(checked, lg.size());
}

TEST(Products, TimelapseFramesComeThroughTheSinkVisibilityFirst) {
    const DemSource& dem = rocky();
    TimelapseRequest r;
    r.frames = instantsBetween(parseZonedInstant("2024-06-21T14:00:00Z", ""), parseZonedInstant("2024-06-21T16:00:00Z", ""),
                               std::chrono::hours(1), 100);
    r.search.threads = 2;
    r.fitDegree = 1;
    std::size_t frames = 0, skies = 0;
    TimelapseSink sink;
    sink.sky = [&](ProductResult&& s) {
        ++skies;
        EXPECT_EQ(names(s), std::vector<std::string>{"sky_k"});
    };
    sink.frame = [&](TimelapseFrame&& f) {
        EXPECT_EQ(f.index, frames++);
        ASSERT_EQ(f.lightmap.bands.size(), 2u);
        EXPECT_EQ(f.lightmap.bands[0].name, "sun_visibility");
        EXPECT_EQ(f.lightmap.bands[1].name, "sun_irradiance");
        EXPECT_EQ(f.localTime, f.lightmap.metadata.at("DEMLIGHT_TIME_LOCAL"));
        EXPECT_GT(f.preview.width, 0u);
        ASSERT_FALSE(f.preview.text.empty());  // the picture carries its time (PNG tEXt)
        EXPECT_EQ(f.preview.text[0], (std::pair<std::string, std::string>{"Creation Time", f.localTime}));
    };
    Grid<float> middle;  // frame 1's sun_irradiance
    sink.frame = [&, check = sink.frame](TimelapseFrame&& f) {
        if (f.index == 1) middle = f.lightmap.bands[1].values;
        check(std::move(f));
    };
    const TimelapseResult res = timelapseProduct(dem, dem.whole(), r, sink);
    EXPECT_EQ(frames, 3u);
    EXPECT_EQ(skies, 1u);
    ASSERT_TRUE(res.fit);
    EXPECT_EQ(res.fit->bands.size(), 3u);  // two coefficients and the RMS residual

    // The sequence product reads the fit back: at a frame's instant it gives that frame within
    // the fit's own residual.
    const std::string fitPath = (std::filesystem::temp_directory_path() /
                                 ("demlight_products_fit_" + std::to_string(::getpid()) + ".tif")).string();
    std::vector<OutputBand> bands;
    for (const auto& b : res.fit->bands) bands.push_back({&b.values, nullptr, b.name, b.unit});
    WriteOptions w;
    w.metadata = res.fit->metadata;
    writeRaster(fitPath, bands, res.fit->ref, w);
    const ProductResult back = sequenceProduct({fitPath, parseZonedInstant("2024-06-21T15:00:00Z", "")});
    std::filesystem::remove(fitPath);
    const Grid<float>& rec = back.band("sun_irradiance").values;
    const Grid<float>& rms = res.fit->band("rms_error").values;
    ASSERT_TRUE(rec.sameShape(middle));
    std::size_t within = 0, valid = 0;
    for (std::size_t k = 0; k < rec.size(); ++k) {
        if (std::isnan(middle.data()[k])) continue;
        ++valid;
        within += std::abs(rec.data()[k] - middle.data()[k]) <= 3 * rms.data()[k] + 1e-6f ? 1 : 0;
    }
    EXPECT_GT(within, valid * 9 / 10);
}

// A frame that says its preview repeats the previous frame's has that frame's pixels, bit for
// bit (a writer reuses what it made of them); night frames after the first do, and the frames
// after the sun has risen do not.
TEST(Products, TimelapsePreviewRepeatsOnlyThePreviousPixels) {
    const DemSource& dem = rocky();
    TimelapseRequest r;
    // Rocky Mountain (UTC-6 in June): deep night at 07:00-08:00 UTC, the sun up at 13:00 UTC.
    r.frames = instantsBetween(parseZonedInstant("2024-06-21T07:00:00Z", ""), parseZonedInstant("2024-06-21T08:00:00Z", ""),
                               std::chrono::minutes(30), 100);
    r.frames.instants.push_back(parseZonedInstant("2024-06-21T13:00:00Z", "").utc);
    r.frames.instants.push_back(parseZonedInstant("2024-06-21T13:30:00Z", "").utc);
    r.search.threads = 2;
    r.lightmaps = false;
    std::vector<bool> repeats;
    Image8 previous;
    TimelapseSink sink;
    sink.frame = [&](TimelapseFrame&& f) {
        repeats.push_back(f.previewRepeats);
        if (f.previewRepeats) {
            EXPECT_EQ(f.preview.rgba, previous.rgba) << "frame " << f.index;
        } else if (f.index > 0) {
            EXPECT_NE(f.preview.rgba, previous.rgba) << "frame " << f.index << " repeats without saying so";
        }
        previous = std::move(f.preview);
    };
    timelapseProduct(dem, dem.whole(), r, sink);
    EXPECT_EQ(repeats, (std::vector<bool>{false, true, true, false, false}));
}

TEST(Products, TimelapsePreviewsAreOfTheWholeDemOnly) {
    const DemSource& dem = rocky();
    TimelapseRequest r;
    r.frames = instantsBetween(parseZonedInstant("2024-06-21T14:00:00Z", ""), parseZonedInstant("2024-06-21T15:00:00Z", ""),
                               std::chrono::hours(1), 100);
    r.search.threads = 2;
    try {
        timelapseProduct(dem, CellWindow{10, 10, 60, 60}, r, TimelapseSink{});
        ADD_FAILURE() << "previews of a window were made";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "previews");
    }
}

TEST(Products, TimelapseFitMeanIsTheSameBitsInAnyOrderOfWindows) {
    // A double running sum drops 2^-60 beside 1 (53-bit significand), so 1 then 1024 x 2^-60
    // sums to 1 while the small values first give 1 + 2^-50; the exact sum gives the latter in
    // any order.
    const float tiny = std::ldexp(1.0f, -60);
    FitStats oneFirst, tinyFirst, left, right;
    oneFirst.add(1.0f);
    for (int i = 0; i < 1024; ++i) oneFirst.add(tiny), tinyFirst.add(tiny), (i < 500 ? left : right).add(tiny);
    tinyFirst.add(1.0f);
    right.add(1.0f);
    left.merge(right);
    const double expected = (1.0 + std::ldexp(1.0, -50)) / 1025.0;
    EXPECT_EQ(oneFirst.meanRms(), expected);
    EXPECT_EQ(tinyFirst.meanRms(), expected);
    EXPECT_EQ(left.meanRms(), expected);
    EXPECT_EQ(left.cells, 1025u);
    EXPECT_EQ(left.worstRms, 1.0);
}

TEST(Products, AWindowIsTheWholeDemsAnswerOnItsCells) {
    // A window computed with its halo lies on the window's georeference and agrees with the
    // whole DEM's answer on its cells (scan lines are anchored to the read window, so the bits
    // may differ: tiled execution makes them identical).
    const DemSource& dem = rocky();
    HorizonRequest r;
    r.azimuthsDeg = {100};
    r.search.threads = 2;
    const CellWindow w{40, 50, 100, 130};
    const HorizonResult whole = horizonProduct(dem, dem.whole(), r);
    const HorizonResult part = horizonProduct(dem, w, r);
    const auto& gt = dem.geometry().band.ref.geoTransform;
    EXPECT_DOUBLE_EQ(part.horizons.ref.geoTransform[0], gt[0] + 40 * gt[1]);
    EXPECT_DOUBLE_EQ(part.horizons.ref.geoTransform[3], gt[3] + 50 * gt[5]);
    const Grid<float>& p = part.horizons.bands[0].values;
    ASSERT_EQ(p.width(), 60u);
    ASSERT_EQ(p.height(), 80u);
    double sum = 0, worst = 0;
    for (std::size_t row = 0; row < p.height(); ++row)
        for (std::size_t col = 0; col < p.width(); ++col) {
            const double d = std::abs(p(col, row) - whole.horizons.bands[0].values(col + 40, row + 50));
            sum += d, worst = std::max(worst, d);
        }
    EXPECT_LT(sum / static_cast<double>(p.size()), 0.05);
    EXPECT_LT(worst, 2.0);
    EXPECT_GE(horizonHaloCells(dem, r), 1u);
}

// sunhours' horizon mode: a given one is kept; auto interpolates (kDefaultStackDirections) only
// on terrain, under quality auto, for periods of at least kAutoStackMinInstants instants.
TEST(Products, SunhoursAutoInterpolatesOnlyLongPeriodsOnTerrainUnderAuto) {
    SunhoursRequest r;
    r.zone = TimeZoneSpec::iana("UTC");
    r.firstDay = r.lastDay = parseDate("2024-06-21");
    r.step = std::chrono::minutes(10);
    EXPECT_EQ(sunhoursInstantCount(r), 145u);  // 00:00, 00:10, ... 23:50 and 24:00
    r.lastDay = parseDate("2024-06-22");
    EXPECT_EQ(sunhoursInstantCount(r), 289u);
    r.step = std::chrono::minutes(7);  // 2880 min = 411 steps of 7 min and 3 min left over
    EXPECT_EQ(sunhoursInstantCount(r), 413u);
    r.step = std::chrono::minutes(10);

    ScenePlan terrain;
    terrain.quality = Quality::Auto;
    ScenePlan surface = terrain;
    surface.surfaceModel = true;
    ScenePlan full = terrain;
    full.quality = Quality::Full;
    EXPECT_GE(sunhoursInstantCount(r), kAutoStackMinInstants);
    EXPECT_EQ(sunhoursStackDirections(r, terrain), kDefaultStackDirections);
    EXPECT_EQ(sunhoursStackDirections(r, surface), 0u);
    EXPECT_EQ(sunhoursStackDirections(r, full), 0u);
    r.lastDay = r.firstDay;  // 145 instants: a sweep per instant costs less than the stack
    EXPECT_LT(sunhoursInstantCount(r), kAutoStackMinInstants);
    EXPECT_EQ(sunhoursStackDirections(r, terrain), 0u);
    r.stackDirections = 16;  // given: kept everywhere
    EXPECT_EQ(sunhoursStackDirections(r, surface), 16u);
    EXPECT_EQ(sunhoursStackDirections(r, full), 16u);
    r.stackDirections = 0;
    r.lastDay = parseDate("2024-06-30");
    EXPECT_EQ(sunhoursStackDirections(r, terrain), 0u);
}

TEST(Products, MessagesNameRequestFieldsNotFlags) {
    const DemSource& dem = rocky();
    const auto message = [](auto&& call) {
        try {
            call();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    SkyRequest sky;
    sky.albedo = 2;
    const std::string a = message([&] { skyProduct(dem, dem.whole(), sky); });
    EXPECT_NE(a.find("albedo 2"), std::string::npos) << a;
    SunRequest sun;
    sun.time = morning();
    sun.search.maxDistanceM = -5;
    const std::string b = message([&] { sunProduct(dem, dem.whole(), sun); });
    EXPECT_NE(b.find("maxDistanceM -5"), std::string::npos) << b;
    HorizonRequest h;
    const std::string c = message([&] { horizonProduct(dem, dem.whole(), h); });
    EXPECT_NE(c.find("azimuthsDeg"), std::string::npos) << c;
    const std::string d = message([&] { horizonProduct(dem, CellWindow{0, 0, 1000, 5}, HorizonRequest{{0}, {}, {}}); });
    EXPECT_NE(d.find("window"), std::string::npos) << d;
    for (const std::string& m : {a, b, c, d}) EXPECT_EQ(m.find("--"), std::string::npos) << m;
}

TEST(Products, AuxiliaryRastersAreCheckedForRangeAndCoverage) {
    const DemSource& dem = rocky();
    // The DEM itself as an "albedo": heights of thousands of metres are not an albedo.
    SkyRequest r;
    r.albedoRaster = kRocky;
    r.directions = 4;
    try {
        skyProduct(dem, dem.whole(), r);
        FAIL() << "heights accepted as albedo";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("albedoRaster"), std::string::npos) << e.what();
    }
    // A raster elsewhere on the earth covers no cell of the DEM.
    r.albedoRaster = kHelens;
    try {
        skyProduct(dem, dem.whole(), r);
        FAIL() << "a raster that misses the DEM was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("covers no cell"), std::string::npos) << e.what();
    }
    // The cloud shadow too: heights as a cloud factor gave light up to 3705.
    LightRequest light;
    light.time = morning();
    light.cloudShadow = kRocky;
    try {
        lightProduct(dem, dem.whole(), light);
        FAIL() << "heights accepted as a cloud shadow";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "cloudShadow");
        EXPECT_NE(std::string(e.what()).find("expected values 0-1"), std::string::npos) << e.what();
    }
}

TEST(Products, RenderDrawsSquareGroundPixels) {
    // Luxembourg's 30" lat/lon grid at 49.8 N: a cell is 0.65 as wide as it is tall on the ground.
    const DemSource dem = DemSource::open(std::string(DEMLIGHT_SAMPLES_DIR) + "/luxembourg_elev_terra.tif");
    RenderRequest r;
    r.time = morning();
    r.search.threads = 2;
    r.skyDirections = 4;
    const RenderResult ground = renderProduct(dem, r);
    r.picture.pixels = PixelGeometry::Cell;
    const RenderResult cell = renderProduct(dem, r);
    EXPECT_EQ(cell.image.width, dem.width());
    EXPECT_EQ(cell.image.height, dem.height());
    const std::size_t mid = dem.height() / 2;
    const double aspect = dem.geometry().terrain.cellWidthM[mid] / dem.geometry().terrain.cellHeightM[mid];
    EXPECT_EQ(ground.image.height, dem.height());
    EXPECT_EQ(ground.image.width, static_cast<std::size_t>(std::lround(static_cast<double>(dem.width()) * aspect)));
    EXPECT_LT(ground.image.width, dem.width());
    EXPECT_GT(ground.skyDirections, 0u);
}

TEST(Products, DescribeDemReportsTheGrid) {
    const DemInfo d = describeDem(*rocky().readWhole());
    EXPECT_EQ(d.width, 152u);
    EXPECT_EQ(d.height, 187u);
    EXPECT_NEAR(d.elevationMinM, 2281, 1);  // the sample's provenance table: 2281 / 4261 m
    EXPECT_NEAR(d.elevationMaxM, 4261, 1);
    EXPECT_LT(d.latMinDeg, d.latMaxDeg);
    EXPECT_FALSE(d.convergenceDeg);  // geographic
    EXPECT_NEAR(d.longestShadowM, d.reliefM / std::tan(5.0 * M_PI / 180.0), 1e-6);
}

TEST(Products, DescribeDemGivesLongitudesAsTheGridHasThem) {
    // A grid written past 180 E (Greenwich as 360) or before 180 W: the extent is the grid's own.
    for (const double west : {359.9, -200.0}) {
        GeoReference ref;
        ref.geoTransform = {west, 0.01, 0, 45.0, 0, -0.01};
        ref.crsWkt = "EPSG:4326";
        const DemInfo d = describeDem(demFromArray(Grid<float>(20, 10, 100.0f), ref, std::nullopt, "grid"));
        EXPECT_NEAR(d.lonMinDeg, west, 1e-9);
        EXPECT_NEAR(d.lonMaxDeg, west + 0.2, 1e-9);
        EXPECT_NEAR(d.latMinDeg, 44.9, 1e-9);
        EXPECT_NEAR(d.latMaxDeg, 45.0, 1e-9);
    }
}

TEST(Products, ColorEncodingNames) {
    EXPECT_EQ(parseColorEncoding("auto", "f"), ColorEncoding::Auto);
    EXPECT_EQ(parseColorEncoding("srgb", "f"), ColorEncoding::Srgb);
    EXPECT_EQ(parseColorEncoding("linear", "f"), ColorEncoding::Linear);
    EXPECT_THROW(parseColorEncoding("gamma", "f"), Error);
}

}  // namespace
}  // namespace demlight
