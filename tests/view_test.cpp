// demlight view on analytic scenes: the maximum-mipmap ray cast against a walk through every
// patch; a cone on a plane whose apex and silhouette land on the pixels a pinhole camera projects
// them to; a pixel looking straight down showing albedo x the `light` product's value of its
// cell; haze thickening with distance; a camera under the terrain refused. And the command on a
// lat/lon DEM, a UTM DEM and a surface model.
#include "cli_runner.h"
#include "demlight/geo/dem_source.h"
#include "demlight/lighting/max_mipmap.h"
#include "demlight/products/light.h"
#include "demlight/products/view.h"
#include "demlight/core/error.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

namespace demlight {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

/// A UTM zone 10 DEM of `values` with 10 m cells whose centre cell (w / 2, h / 2) has its centre
/// at x 500000, y 5000000 (the zone's central meridian: no grid convergence).
DemSource utmDem(const Grid<float>& values) {
    const double x0 = 500000.0 - 10.0 * (static_cast<double>(values.width() / 2) + 0.5);
    const double y0 = 5000000.0 + 10.0 * (static_cast<double>(values.height() / 2) + 0.5);
    return DemSource(demFromArray(values, GeoReference{{x0, 10, 0, y0, 0, -10}, "EPSG:32610"}, std::nullopt, "scene"));
}

ZonedInstant morning() { return parseZonedInstant("2024-06-21T18:00Z", ""); }

// Both find the first point where the ray meets the bilinear surface from above; with holes
// (nodata) a ray that fell through one passes under the patches beyond (no walls), both alike.
TEST(MaxMipmap, MeetsTheSurfaceWhereAWalkThroughEveryPatchDoes) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Grid<float> h(53, 41);
    for (std::size_t r = 0; r < h.height(); ++r)
        for (std::size_t c = 0; c < h.width(); ++c)
            h(c, r) = static_cast<float>(40 * std::sin(0.3 * c) * std::cos(0.2 * r) + 10 * unit(rng));
    Grid<float> holes = h;
    for (int k = 0; k < 40; ++k) holes(static_cast<std::size_t>(unit(rng) * 53), static_cast<std::size_t>(unit(rng) * 41)) = NAN;
    for (const Grid<float>* field : {&h, &holes}) {
        const MaxMipmap mm(*field);
        int hits = 0;
        for (int i = 0; i < 4000; ++i) {
            // From above every height (<= 50), most over the field, some from beyond its sides.
            GridRay ray{-10 + 73 * unit(rng), -10 + 61 * unit(rng), 60 + 80 * unit(rng), unit(rng) - 0.5,
                        unit(rng) - 0.5, -0.05 - 3 * unit(rng)};
            if (i % 7 == 0) ray.dx = 0;  // along a grid axis too
            if (i % 11 == 0) ray.dy = 0;
            const auto fast = mm.cast(ray, 1e9);
            const auto walk = castRayThroughEveryPatch(*field, ray, 1e9);
            ASSERT_EQ(fast.has_value(), walk.has_value()) << "ray " << i;
            if (!fast) continue;
            ++hits;
            EXPECT_NEAR(fast->t, walk->t, 1e-9 * (1 + walk->t)) << "ray " << i;
            if (field != &h) continue;
            // On the bilinear surface, coming down to it.
            EXPECT_LT(ray.dz, 0);
            const auto c = static_cast<std::size_t>(std::min(fast->x, 51.0));
            const auto r = static_cast<std::size_t>(std::min(fast->y, 39.0));
            const double u = fast->x - c, v = fast->y - r;
            const double surface =
                (1 - v) * ((1 - u) * h(c, r) + u * h(c + 1, r)) + v * ((1 - u) * h(c, r + 1) + u * h(c + 1, r + 1));
            EXPECT_NEAR(fast->z, surface, 1e-6) << "ray " << i;
        }
        EXPECT_GT(hits, 1000);
    }
}

/// The cone of CameraSeesTheConeWhereAPinholeProjectsIt: a plane at 100 m and a cone of radius
/// 600 m rising 500 m to its apex at the centre cell.
constexpr double kPlaneM = 100, kConeRadiusM = 600, kConeHeightM = 500;
Grid<float> coneOnPlane() {
    Grid<float> h(241, 241);
    for (std::size_t r = 0; r < 241; ++r)
        for (std::size_t c = 0; c < 241; ++c) {
            const double d = 10.0 * std::hypot(static_cast<double>(c) - 120, static_cast<double>(r) - 120);
            h(c, r) = static_cast<float>(kPlaneM + kConeHeightM * std::max(0.0, 1 - d / kConeRadiusM));
        }
    return h;
}

ViewRequest plainView(double eyeX, double eyeY, double eyeH, double targetX, double targetY, double targetH,
                      std::size_t width, std::size_t height, double fovDeg) {
    ViewRequest r;
    r.time = morning();
    r.camera.eye = ViewPoint{eyeX, eyeY, eyeH, false};
    r.camera.target = ViewPoint{targetX, targetY, targetH, false};
    r.camera.width = width;
    r.camera.height = height;
    r.camera.fieldOfViewDeg = fovDeg;
    r.atmosphere.haze = false;
    r.atmosphere.sky = false;
    r.search.threads = 2;
    return r;
}

TEST(View, CameraSeesTheConeWhereAPinholeProjectsIt) {
    const DemSource dem = utmDem(coneOnPlane());
    // 2.5 km south of the apex at 350 m, looking due north, level: forward = north, right = east.
    const std::size_t W = 641, H = 481;
    const double fovDeg = 40, eyeH = 350, eyeSouthM = 2500;
    const ViewResult v = viewProduct(dem, plainView(500000, 5000000 - eyeSouthM, eyeH, 500000, 5000000, eyeH, W, H, fovDeg));
    const double rEff = kEarthRadiusM / (1 - kDefaultRefraction);
    const double tanH = std::tan(0.5 * fovDeg * M_PI / 180), tanV = tanH * H / W;
    // A point east dE, north dN and up dU of the eye (before the earth's curvature lowers it).
    const auto project = [&](double dE, double dN, double dU) {
        const double u = dU - (dE * dE + dN * dN) / (2 * rEff);
        return std::array<double, 2>{0.5 * W * (1 + dE / dN / tanH), 0.5 * H * (1 - u / dN / tanV)};
    };
    const auto opaque = [&](double x, double y) {
        const auto px = static_cast<std::size_t>(std::floor(x)), py = static_cast<std::size_t>(std::floor(y));
        return v.view.image.rgba[(py * W + px) * 4 + 3] == 255;
    };
    // The apex: the top of the cone in its column is within a pixel of its projection.
    const auto apex = project(0, eyeSouthM, kPlaneM + kConeHeightM - eyeH);
    std::size_t top = 0;
    while (top < H && !opaque(apex[0], static_cast<double>(top) + 0.5)) ++top;
    EXPECT_NEAR(static_cast<double>(top) + 0.5, apex[1], 1.0) << "apex projected at row " << apex[1];
    EXPECT_FALSE(opaque(apex[0], apex[1] - 1.0));
    EXPECT_TRUE(opaque(apex[0], apex[1] + 1.0));

    // The silhouette: the cone's generators whose tangent planes hold the eye (the normal along
    // the generator at angle phi is (h cos phi, h sin phi, R); (eye - apex) . n = 0).
    const double aE = 0, aN = eyeSouthM, aU = kPlaneM + kConeHeightM - eyeH;  // apex from the eye
    const double s = -kConeRadiusM * (-aU) / (kConeHeightM * -aN);            // sin phi
    for (double phi : {std::asin(s), M_PI - std::asin(s)}) {
        const double side = std::cos(phi) > 0 ? 1.0 : -1.0;  // east or west of the axis
        for (double f : {0.2, 0.4, 0.6}) {
            const double dE = aE + f * kConeRadiusM * std::cos(phi), dN = aN + f * kConeRadiusM * std::sin(phi);
            const double dU = aU - f * kConeHeightM;
            const auto p = project(dE, dN, dU);
            EXPECT_TRUE(opaque(p[0] - side, p[1])) << "inside the silhouette at " << p[0] << ", " << p[1];
            EXPECT_FALSE(opaque(p[0] + side, p[1])) << "outside the silhouette at " << p[0] << ", " << p[1];
        }
    }
}

TEST(View, APixelLookingStraightDownHasTheLightOfItsCell) {
    Grid<float> h(61, 61);
    for (std::size_t r = 0; r < 61; ++r)
        for (std::size_t c = 0; c < 61; ++c)
            h(c, r) = static_cast<float>(100 + 30 * std::sin(c / 5.0) * std::cos(r / 7.0) + 0.7 * c);
    const DemSource dem = utmDem(h);
    LightRequest lr;
    lr.time = morning();
    lr.albedo = 0.5;
    lr.search.threads = 2;
    const LightResult light = lightProduct(dem, dem.whole(), lr);
    const Grid<float>& lit = light.band("light").values;
    // Over cells east of the centre (their light differs from their neighbours').
    for (std::size_t c : {30u, 33u, 37u}) {
        const double x = 500000 + 10.0 * (static_cast<double>(c) - 30), y = 5000000;
        ViewRequest r = plainView(x, y, 900, x, y, 0, 11, 11, 10);
        r.albedo = 0.5;
        r.sunColor = {1, 1, 1};
        r.skyColor = {1, 1, 1};
        const ViewResult v = viewProduct(dem, r);
        const float* centre = v.view.linear.data() + (5 * 11 + 5) * 3;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(centre[k], 0.5 * lit(c, 30), 1e-4) << "cell " << c;
        // Its neighbour differs: the comparison can tell cells apart.
        EXPECT_GT(std::abs(lit(c + 1, 30) - lit(c, 30)) + std::abs(lit(c, 31) - lit(c, 30)), 1e-3);
    }
}

TEST(View, HazeThickensWithDistance) {
    ViewAtmosphere a;
    for (double z : {0.0, 500.0, 3000.0}) {
        double last = 1.0;
        EXPECT_EQ(hazeTransmittance(a, 0, z, z).g, 1.0);
        for (double d = 100; d < 2e5; d *= 1.5) {
            const Rgb t = hazeTransmittance(a, d, z, z + 0.01 * d);
            EXPECT_LT(t.g, last) << d;
            EXPECT_LT(t.b, t.r) << "blue is scattered more";
            last = t.g;
        }
    }
    ViewAtmosphere off = a;
    off.haze = false;
    EXPECT_EQ(hazeTransmittance(off, 5e4, 0, 0).b, 1.0);

    // A flat lit plane seen towards its far edge: the further the ground, the nearer its colour
    // to the haze's (greener ground fades to the haze's blue-grey).
    Grid<float> flat(401, 401, 0.0f);
    const DemSource dem = utmDem(flat);
    ViewRequest r = plainView(500000, 5000000 - 1995, 40, 500000, 5000000 + 2000, 0, 64, 96, 20);
    r.atmosphere.haze = true;
    r.atmosphere.visibilityKm = 5;
    r.albedo = 0.4;
    const ViewResult v = viewProduct(dem, r);
    r.atmosphere.haze = false;
    const ViewResult clear = viewProduct(dem, r);
    double lastDistance = 0, lastShare = -1;
    int rows = 0;
    for (std::size_t y = 95; y > 0; --y) {
        const std::size_t k = y * 64 + 32;
        if (!std::isfinite(v.view.distanceM[k])) break;
        const Rgb in = hazeInscatter(ViewLight{v.sunAzimuthDeg, v.sunElevationDeg, 0, 0.53, {1.64, 1.27, 0.99}, {0.16, 0.20, 0.28}},
                                     pixelDirection(v.camera, 32.5, static_cast<double>(y) + 0.5));
        // The share of haze in the pixel: 0 for clear ground, 1 for haze alone.
        const double share = (clear.view.linear[k * 3 + 1] - v.view.linear[k * 3 + 1]) /
                             (clear.view.linear[k * 3 + 1] - in.g);
        EXPECT_GT(v.view.distanceM[k], lastDistance);
        EXPECT_GT(share, lastShare) << "row " << y;
        lastDistance = v.view.distanceM[k];
        lastShare = share;
        ++rows;
    }
    EXPECT_GT(rows, 30);
    EXPECT_GT(lastShare, 0.3);
}

TEST(View, ACameraUnderTheTerrainIsRefused) {
    const DemSource dem = utmDem(coneOnPlane());
    try {
        viewProduct(dem, plainView(500000, 5000000, 300, 500000, 5001000, 300, 32, 24, 40));
        FAIL() << "a camera inside the cone was accepted";
    } catch (const FieldError& e) {
        EXPECT_EQ(e.field(), "eye");
        EXPECT_NE(std::string(e.what()).find("under the terrain"), std::string::npos) << e.what();
    }
    // An orbit whose camera dips below the ground in front of it.
    ViewRequest r;
    r.time = morning();
    r.camera.elevationDeg = -60;
    r.camera.distanceM = 500;
    r.camera.width = 32;
    r.camera.height = 24;
    EXPECT_THROW(viewProduct(dem, r), FieldError);
}

TEST(View, LandscapeAlbedoIsVegetationRockSnowAndSea) {
    const Rgb low = landscapeAlbedo(500, 1.0, 2000, 3000);
    const Rgb cliff = landscapeAlbedo(500, std::cos(60 * M_PI / 180), 2000, 3000);
    const Rgb high = landscapeAlbedo(2500, 1.0, 2000, 3000);
    const Rgb snow = landscapeAlbedo(3500, 1.0, 2000, 3000);
    const Rgb snowWall = landscapeAlbedo(3500, std::cos(70 * M_PI / 180), 2000, 3000);
    const Rgb sea = landscapeAlbedo(0, 1.0, 2000, 3000);
    EXPECT_GT(low.g, low.r);          // green
    EXPECT_GT(cliff.r, 2 * low.r);    // steep: rock
    EXPECT_NEAR(cliff.r, high.r, 1e-12);  // above the tree line: rock too
    EXPECT_GT(snow.b, 0.7);           // snow
    EXPECT_NEAR(snowWall.r, cliff.r, 1e-12);  // no snow on a wall
    EXPECT_NEAR(sea.b, kSeaAlbedo.b, 1e-12);
    EXPECT_GT(landscapeAlbedo(0, 0.99, 2000, 3000).g, sea.g);  // a slope at 0 m is land
}

// The command on a lat/lon DEM, a UTM DEM with nodata as sea, and a surface model (shared
// data; skipped without it), and its refusal of a camera under the ground.
TEST(ViewCli, DrawsLatLonUtmAndSurfaceModels) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("demlight_view_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string samples = DEMLIGHT_SAMPLES_DIR;
    std::vector<std::string> runs = {
        samples + "/luxembourg_elev_terra.tif --time 2024-06-21T08:00Z --exaggeration 3",
        samples + "/mount_st_helens_1980_usgs.dem --time 2024-06-21T07:30 --tz America/Los_Angeles --nodata sea",
    };
    const std::string dsm = std::string(DEMLIGHT_SHARED_DEM_DIR) + "/../dsm/nyc_ccny_harlem_1m_dsm.tif";
    if (fs::exists(dsm)) runs.push_back(dsm + " --time 2024-06-21T15:00Z --camera-elevation 35");
    int i = 0;
    for (const std::string& run : runs) {
        const std::string out = (dir / ("v" + std::to_string(i++) + ".png")).string();
        const auto r = testing::runDemlight("-q view " + run + " -o " + out + " --size 96x64");
        EXPECT_EQ(r.exitCode, 0) << run << "\n" << r.err;
        EXPECT_TRUE(fs::exists(out)) << run;
    }
    const auto under = testing::runDemlight("-q view " + samples + "/mount_st_helens_1980_usgs.dem --time 2024-06-21T15:00Z "
                                            "--eye 46.2,-122.19,100 -o " + (dir / "under.png").string());
    EXPECT_NE(under.exitCode, 0);
    EXPECT_NE(under.err.find("under the terrain"), std::string::npos) << under.err;
    EXPECT_FALSE(fs::exists(dir / "under.png"));
    fs::remove_all(dir);
}

/// An RGBA picture's bytes and size.
std::vector<std::uint8_t> pictureBytes(const std::string& path, int& width, int& height) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        ADD_FAILURE() << path << ": " << OIIO::geterror();
        return {};
    }
    width = in->spec().width;
    height = in->spec().height;
    std::vector<std::uint8_t> px(static_cast<std::size_t>(width) * height * 4);
    EXPECT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
    return px;
}

// A time-lapse in the view draws each frame as `view` draws its instant (its sun term per frame,
// the sky term once, the same light); camera options without --view are refused.
TEST(ViewCli, TimelapseFramesAreTheViewsOfTheirInstants) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("demlight_view_tl_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string dem = std::string(DEMLIGHT_SAMPLES_DIR) + "/rocky_mountain_np_dem.tif";
    const std::string camera = " --size 96x64 --camera-azimuth 150 --camera-elevation 30";
    const auto tl = testing::runDemlight("-q timelapse " + dem + " -o " + (dir / "tl").string() +
                                         " --start 2024-06-21T14:00Z --end 2024-06-21T17:00Z --step 3h --view --formats png,gif" +
                                         camera);
    ASSERT_EQ(tl.exitCode, 0) << tl.err;
    EXPECT_TRUE(fs::exists(dir / "tl" / "timelapse.gif"));
    for (const auto& [frame, time] : {std::pair{"frame_000.png", "2024-06-21T14:00Z"}, std::pair{"frame_001.png", "2024-06-21T17:00Z"}}) {
        const std::string single = (dir / (std::string("view_") + frame)).string();
        const auto v = testing::runDemlight("-q view " + dem + " -o " + single + " --time " + time + camera);
        ASSERT_EQ(v.exitCode, 0) << v.err;
        int w1 = 0, h1 = 0, w2 = 0, h2 = 0;
        const auto a = pictureBytes((dir / "tl" / frame).string(), w1, h1);
        const auto b = pictureBytes(single, w2, h2);
        ASSERT_EQ(w1, 96);
        ASSERT_EQ(h1, 64);
        ASSERT_EQ(a.size(), b.size());
        int worst = 0;
        for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(int(a[i]) - int(b[i])));
        EXPECT_LE(worst, 1) << frame;
    }
    // The two frames differ (the sun moved): the comparison can tell instants apart.
    int w = 0, h = 0;
    EXPECT_NE(pictureBytes((dir / "tl" / "frame_000.png").string(), w, h),
              pictureBytes((dir / "tl" / "frame_001.png").string(), w, h));
    const auto without = testing::runDemlight("-q timelapse " + dem + " -o " + (dir / "tl2").string() +
                                              " --start 2024-06-21T14:00Z --end 2024-06-21T17:00Z --step 3h --camera-azimuth 10");
    EXPECT_NE(without.exitCode, 0);
    EXPECT_NE(without.err.find("--view"), std::string::npos) << without.err;
    fs::remove_all(dir);
}

}  // namespace
}  // namespace demlight
