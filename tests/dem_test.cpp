// Per-cell metric geometry: ellipsoidal cell sizes of lat/lon grids against published lengths of
// a degree, and meridian convergence of a projected grid against GeographicLib's exact
// transverse Mercator (an implementation independent of the PROJ path demlight uses).
#include "demlight/geo/dem.h"
#include "demlight/geo/raster.h"
#include "demlight/core/error.h"

#include <GeographicLib/TransverseMercator.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>

namespace demlight {
namespace {

namespace fs = std::filesystem;

const std::string kWgs84Wkt = R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433],AXIS["Latitude",NORTH],AXIS["Longitude",EAST],AUTHORITY["EPSG","4326"]])";
const std::string kUtm33Wkt = R"(PROJCS["WGS 84 / UTM zone 33N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",15],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32633"]])";

std::string writeGrid(const std::string& name, std::size_t w, std::size_t h,
                      const GeoReference& ref) {
    const fs::path dir = fs::temp_directory_path() / "demlight_test_dem";
    fs::create_directories(dir);
    const std::string path = (dir / name).string();
    Grid<float> z(w, h, 100.0f);
    writeRaster(path, {{&z, nullptr, "height", "m"}}, ref, {});
    return path;
}

// Length of one degree on WGS84 (km), as tabulated in standard geodesy references
// (e.g. the "length of a degree" table for the WGS84 ellipsoid), to the metre.
struct DegreeLength {
    double latDeg, latKm, lonKm;
};
constexpr DegreeLength kDegreeLengths[] = {
    {0, 110.574, 111.320},  {15, 110.649, 107.551}, {30, 110.852, 96.486},
    {45, 111.133, 78.847},  {60, 111.412, 55.800},  {75, 111.618, 28.902},
};

TEST(Metrics, GeographicCellSizesMatchPublishedDegreeLengths) {
    // One-degree cells whose centres sit on whole degrees: row r has centre latitude 80 - r.
    GeoReference ref;
    ref.geoTransform = {-0.5, 1.0, 0, 80.5, 0, -1.0};
    ref.crsWkt = kWgs84Wkt;
    const Dem dem = loadDem(writeGrid("deg.tif", 2, 161, ref));
    ASSERT_TRUE(dem.crs.geographic);
    for (const auto& d : kDegreeLengths) {
        const auto row = static_cast<std::size_t>(80 - d.latDeg);
        SCOPED_TRACE(d.latDeg);
        EXPECT_NEAR(dem.terrain.rowLatitudeDeg[row], d.latDeg, 1e-12);
        EXPECT_NEAR(dem.terrain.cellHeightM[row], d.latKm * 1000, 1.5);
        EXPECT_NEAR(dem.terrain.cellWidthM[row], d.lonKm * 1000, 1.5);
    }
    EXPECT_TRUE(dem.terrain.convergence.empty());
}

TEST(Metrics, ProjectedCellSizeFromGeotransform) {
    GeoReference ref;
    ref.geoTransform = {500000, 25, 0, 6650000, 0, -20};
    ref.crsWkt = kUtm33Wkt;
    const Dem dem = loadDem(writeGrid("utm_cells.tif", 3, 3, ref));
    EXPECT_FALSE(dem.crs.geographic);
    ASSERT_TRUE(dem.crs.epsg.has_value());
    EXPECT_EQ(*dem.crs.epsg, 32633);
    EXPECT_DOUBLE_EQ(dem.terrain.cellWidthM[1], 25.0);
    EXPECT_DOUBLE_EQ(dem.terrain.cellHeightM[1], 20.0);
}

TEST(Metrics, ConvergenceAtUtmZoneEdgeMatchesGeographicLib) {
    // 200 km east of the central meridian (15 E) at about 60 N: reaches 18.6 E, past the
    // zone edge, where convergence exceeds 2.5 degrees.
    GeoReference ref;
    ref.geoTransform = {500000, 1000, 0, 6700000, 0, -1000};
    ref.crsWkt = kUtm33Wkt;
    const Dem dem = loadDem(writeGrid("utm_conv.tif", 200, 100, ref));
    const auto& tm = GeographicLib::TransverseMercator::UTM();
    const auto& field = dem.terrain.convergence;
    ASSERT_FALSE(field.empty());
    double maxGamma = 0;
    for (std::size_t j = 0; j < field.gammaDeg.height(); ++j) {
        for (std::size_t i = 0; i < field.gammaDeg.width(); ++i) {
            const double col = static_cast<double>(std::min<std::size_t>(i * field.stepCells, 199)) + 0.5;
            const double row = static_cast<double>(std::min<std::size_t>(j * field.stepCells, 99)) + 0.5;
            const double x = 500000 + col * 1000 - 500000;  // false easting removed
            const double y = 6700000 - row * 1000;
            double lat, lon, gamma, k;
            tm.Reverse(15.0, x, y, lat, lon, gamma, k);
            EXPECT_NEAR(field.gammaDeg(i, j), gamma, 2e-4) << "col " << col << " row " << row;
            maxGamma = std::max(maxGamma, gamma);
        }
    }
    EXPECT_GT(maxGamma, 2.5);
    // Sign: east of the central meridian in the northern hemisphere grid north lies east of
    // true north, so gamma is positive.
    EXPECT_GT(field.at(199, 50), 2.5);
}

/// Equal values, NaN equal to NaN.
bool sameCells(const Grid<float>& a, const Grid<float>& b) {
    if (a.width() != b.width() || a.height() != b.height()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(a.data()[i] == b.data()[i] || (std::isnan(a.data()[i]) && std::isnan(b.data()[i])))) return false;
    return true;
}

// Values held in memory (the Python module's arrays) read as the file holding them does:
// heights, nodata cells, CRS, cell sizes and convergence, under the caller's name.
TEST(DemFromArray, ReadsAsTheFileTheValuesCameFrom) {
    const Dem file = loadDem(std::string(DEMLIGHT_SAMPLES_DIR) + "/mount_st_helens_1980_usgs.dem");
    ASSERT_TRUE(file.band.nodata.has_value());
    ASSERT_GT(file.band.nodataCount, 0u);
    Grid<float> raw = file.band.values;  // NaN at nodata: put the file's nodata value back
    for (float& v : raw.values())
        if (std::isnan(v)) v = static_cast<float>(*file.band.nodata);
    const Dem array = demFromArray(raw, file.band.ref, file.band.nodata, "<array>");
    EXPECT_EQ(array.band.path, "<array>");
    EXPECT_EQ(array.band.nodata, file.band.nodata);
    EXPECT_EQ(array.band.nodataCount, file.band.nodataCount);
    EXPECT_TRUE(sameCells(array.terrain.heightsM, file.terrain.heightsM));
    EXPECT_EQ(array.crs.epsg, file.crs.epsg);
    EXPECT_EQ(array.crs.name, file.crs.name);
    EXPECT_EQ(array.terrain.cellWidthM, file.terrain.cellWidthM);
    EXPECT_EQ(array.terrain.rowLatitudeDeg, file.terrain.rowLatitudeDeg);
    EXPECT_TRUE(sameCells(array.terrain.convergence.gammaDeg, file.terrain.convergence.gammaDeg));
}

// An array gets a file's checks, and the message names the array, not the memory file.
TEST(DemFromArray, RefusesWhatAFileWouldBeRefusedFor) {
    const Grid<float> z(20, 10, 100.0f);
    GeoReference ref;
    ref.geoTransform = {500000, 30, 0, 6700000, 0, -30};
    try {
        demFromArray(z, ref, std::nullopt, "heights");  // no CRS
        FAIL() << "an array without a CRS was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("'heights' has no coordinate reference system"), std::string::npos) << message;
        EXPECT_EQ(message.find("/vsimem"), std::string::npos) << message;
    }
    ref.crsWkt = "EPSG:32633";
    ref.geoTransform[5] = 30;  // south-up
    EXPECT_THROW(demFromArray(z, ref, std::nullopt, "heights"), Error);
    ref.geoTransform[5] = -30;
    const Dem dem = demFromArray(z, ref, std::nullopt, "heights");
    EXPECT_EQ(dem.crs.epsg, 32633);
    EXPECT_DOUBLE_EQ(dem.terrain.cellWidthM.front(), 30.0);
}

TEST(DemFromArray, LatitudesBeyondThePolesAreRefusedNamingThem) {
    const Grid<float> z(20, 20, 100.0f);
    GeoReference ref;
    ref.crsWkt = "EPSG:4326";
    for (const double north : {91.0, -88.9}) {  // 89 .. 91 N; 90.9 .. 88.9 S
        ref.geoTransform = {10, 0.1, 0, north, 0, -0.1};
        try {
            demFromArray(z, ref, std::nullopt, "heights");
            FAIL() << "rows past a pole were accepted (north edge " << north << ")";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("beyond the poles"), std::string::npos) << e.what();
        }
    }
    ref.geoTransform = {10, 0.1, 0, 90, 0, -0.1};  // up to the pole is a grid
    EXPECT_NEAR(demFromArray(z, ref, std::nullopt, "heights").terrain.rowLatitudeDeg.front(), 89.95, 1e-9);
}

}  // namespace
}  // namespace demlight
