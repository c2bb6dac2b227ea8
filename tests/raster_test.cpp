// Raster I/O: reading real samples (nodata kinds), refusing bad georeferencing, and a write/read
// round trip that keeps CRS, geotransform, nodata, descriptions, units and metadata.
#include "demlight/geo/dem.h"
#include "demlight/geo/raster.h"
#include "demlight/geo/tiff_tiles.h"
#include "demlight/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <filesystem>
#include <fstream>

namespace demlight {
namespace {

namespace fs = std::filesystem;

const std::string kSamples = DEMLIGHT_SAMPLES_DIR;
const std::string kUtmWkt = R"(PROJCS["WGS 84 / UTM zone 11N",GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],PARAMETER["latitude_of_origin",0],PARAMETER["central_meridian",-117],PARAMETER["scale_factor",0.9996],PARAMETER["false_easting",500000],PARAMETER["false_northing",0],UNIT["metre",1],AUTHORITY["EPSG","32611"]])";

/// A fresh empty folder for one test's files.
fs::path scratchDir(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("demlight_test_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::size_t countNan(const Grid<float>& g) {
    std::size_t n = 0;
    for (float v : g.values()) n += std::isnan(v);
    return n;
}

TEST(ReadRaster, Int16NodataBecomesNan) {
    // Provenance README: 4151 cells (2.7 %) of -32767 in the corners.
    const RasterBand b = readRasterBand(kSamples + "/mount_st_helens_1980_usgs.dem");
    EXPECT_EQ(b.values.width(), 327u);
    EXPECT_EQ(b.values.height(), 468u);
    ASSERT_TRUE(b.nodata.has_value());
    EXPECT_EQ(*b.nodata, -32767.0);
    EXPECT_EQ(b.nodataCount, 4151u);
    EXPECT_EQ(countNan(b.values), 4151u);
}

TEST(ReadRaster, UInt16NodataDeclaredButAbsent) {
    const RasterBand b = readRasterBand(kSamples + "/rocky_mountain_np_dem.tif");
    ASSERT_TRUE(b.nodata.has_value());
    EXPECT_EQ(*b.nodata, 65535.0);
    EXPECT_EQ(b.nodataCount, 0u);
}

TEST(ReadRaster, LuxembourgBorderIsNodata) {
    const RasterBand b = readRasterBand(kSamples + "/luxembourg_elev_terra.tif");
    EXPECT_EQ(b.nodataCount, 3942u);  // README: 3942 cells outside the national border
}

TEST(ReadRaster, RefusesMissingFileWithItsName) {
    try {
        readRasterBand("/nonexistent/dem.tif");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/dem.tif"), std::string::npos);
    }
}

TEST(ReadRaster, RefusesNonRaster) {
    const fs::path dir = scratchDir("nonraster");
    const fs::path p = dir / "notes.txt";
    std::ofstream(p) << "not a raster\n";
    EXPECT_THROW(readRasterBand(p.string()), Error);
}

TEST(WriteRaster, RoundTripKeepsGeoreferencingAndDescriptions) {
    const fs::path dir = scratchDir("roundtrip");
    Grid<float> a(4, 3, 1.5f);
    a(1, 1) = std::numeric_limits<float>::quiet_NaN();
    Grid<std::uint8_t> m(4, 3, 0);
    m(2, 0) = 1;
    GeoReference ref;
    ref.geoTransform = {350000, 30, 0, 3800000, 0, -30};
    ref.crsWkt = kUtmWkt;
    WriteOptions opt;
    opt.metadata["DEMLIGHT_COMMAND"] = "demlight test";
    opt.nodata = -32768;
    const std::string out = (dir / "out.tif").string();
    writeRaster(out, {{&a, nullptr, "sun_visibility", "fraction"}, {nullptr, &m, "truncated", ""}},
                ref, opt);

    const RasterSummary s = inspectRaster(out);
    EXPECT_EQ(s.driver, "GTiff");
    EXPECT_EQ(s.width, 4u);
    EXPECT_EQ(s.height, 3u);
    EXPECT_EQ(s.ref.geoTransform, ref.geoTransform);
    EXPECT_NE(s.ref.crsWkt.find("UTM zone 11N"), std::string::npos);
    EXPECT_EQ(s.descriptions, (std::vector<std::string>{"sun_visibility", "truncated"}));
    EXPECT_EQ(s.units[0], "fraction");
    ASSERT_TRUE(s.nodata.has_value());
    EXPECT_EQ(*s.nodata, -32768.0);
    EXPECT_EQ(s.metadata.at("DEMLIGHT_COMMAND"), "demlight test");
    EXPECT_EQ(s.imageStructure.at("COMPRESSION"), "ZSTD");
    EXPECT_EQ(s.imageStructure.at("INTERLEAVE"), "BAND");

    const RasterBand back = readRasterBand(out);
    EXPECT_TRUE(std::isnan(back.values(1, 1)));
    EXPECT_EQ(back.values(0, 0), 1.5f);
    // No temporary file is left in the folder.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(WriteRaster, CogAndCreationOptions) {
    const fs::path dir = scratchDir("cog");
    Grid<float> a(300, 200, 2.0f);
    GeoReference ref;
    ref.geoTransform = {350000, 30, 0, 3800000, 0, -30};
    ref.crsWkt = kUtmWkt;
    WriteOptions opt;
    opt.format = "COG";
    opt.creationOptions = {"COMPRESS=LZW"};
    const std::string out = (dir / "out.tif").string();
    writeRaster(out, {{&a, nullptr, "x", "m"}}, ref, opt);
    const RasterSummary s = inspectRaster(out);
    EXPECT_EQ(s.imageStructure.at("LAYOUT"), "COG");
    EXPECT_EQ(s.imageStructure.at("COMPRESSION"), "LZW");
}

TEST(WriteRaster, RefusesBadTargetsWithoutLeavingFiles) {
    const fs::path dir = scratchDir("badtarget");
    Grid<float> a(2, 2, 0.0f);
    GeoReference ref;
    ref.crsWkt = kUtmWkt;
    EXPECT_THROW(writeRaster((dir / "missing" / "out.tif").string(), {{&a, nullptr, "x", ""}}, ref, {}),
                 Error);
    const std::string in = (dir / "in.tif").string();
    writeRaster(in, {{&a, nullptr, "x", ""}}, ref, {});
    EXPECT_THROW(writeRaster(in, {{&a, nullptr, "x", ""}}, ref, {}, in), Error);
    WriteOptions bad;
    bad.creationOptions = {"NOEQUALS"};
    EXPECT_THROW(writeRaster((dir / "o.tif").string(), {{&a, nullptr, "x", ""}}, ref, bad), Error);
    EXPECT_FALSE(fs::exists(dir / "o.tif"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

// A copy with new metadata has the source's cells, bands and georeference, the new values of
// the items given and the source's other items; it leaves no temporary or sidecar file, and a
// missing source is an error that leaves nothing at the target.
TEST(WriteRaster, CopyWithMetadataKeepsTheCellsAndChangesTheItems) {
    const fs::path dir = scratchDir("copymeta");
    Grid<float> a(300, 260, 0.0f), b(300, 260, 0.25f);
    for (std::size_t i = 0; i < 300; ++i) a(i, i % 260) = std::numeric_limits<float>::quiet_NaN();
    b(7, 9) = 3.5f;
    GeoReference ref;
    ref.geoTransform = {350000, 30, 0, 3800000, 0, -30};
    ref.crsWkt = kUtmWkt;
    WriteOptions opt;
    opt.metadata = {{"DEMLIGHT_FRAME", "0"}, {"DEMLIGHT_TIME_UTC", "2024-06-21T07:00:00Z"}, {"DEMLIGHT_KEPT", "k"}};
    opt.nodata = -32768;
    const std::string src = (dir / "frame_000.tif").string(), out = (dir / "frame_001.tif").string();
    writeRaster(src, {{&a, nullptr, "sun_visibility", "fraction"}, {&b, nullptr, "sun_irradiance", "W"}}, ref, opt);
    copyRasterWithMetadata(src, out, {{"DEMLIGHT_FRAME", "1"}, {"DEMLIGHT_TIME_UTC", "2024-06-21T07:15:00.5Z longer"}});

    const RasterSummary s = inspectRaster(out), s0 = inspectRaster(src);
    EXPECT_EQ(s.metadata.at("DEMLIGHT_FRAME"), "1");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_TIME_UTC"), "2024-06-21T07:15:00.5Z longer");
    EXPECT_EQ(s.metadata.at("DEMLIGHT_KEPT"), "k");
    EXPECT_EQ(s0.metadata.at("DEMLIGHT_FRAME"), "0");  // the source is left as it was
    EXPECT_EQ(s.ref.geoTransform, ref.geoTransform);
    EXPECT_NE(s.ref.crsWkt.find("UTM zone 11N"), std::string::npos);
    EXPECT_EQ(s.descriptions, s0.descriptions);
    EXPECT_EQ(s.units, s0.units);
    ASSERT_TRUE(s.nodata.has_value());
    EXPECT_EQ(*s.nodata, -32768.0);
    EXPECT_EQ(s.imageStructure, s0.imageStructure);
    const std::vector<Grid<float>> back = readRasterBands(out);
    ASSERT_EQ(back.size(), 2u);
    for (std::size_t k = 0; k < a.size(); ++k) {
        ASSERT_EQ(std::isnan(back[0].data()[k]), std::isnan(a.data()[k])) << k;
        if (!std::isnan(a.data()[k])) {
            ASSERT_EQ(back[0].data()[k], a.data()[k]) << k;
        }
        ASSERT_EQ(back[1].data()[k], b.data()[k]) << k;
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);  // no .aux.xml, no .tmp

    EXPECT_THROW(copyRasterWithMetadata((dir / "none.tif").string(), (dir / "x.tif").string(), {}), Error);
    EXPECT_FALSE(fs::exists(dir / "x.tif"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
}

TEST(ReadRaster, RefusesRotatedGeotransformAndMissingCrs) {
    const fs::path dir = scratchDir("badgeo");
    Grid<float> a(3, 3, 5.0f);
    GeoReference rotated;
    rotated.geoTransform = {0, 30, 5, 0, 5, -30};
    rotated.crsWkt = kUtmWkt;
    writeRaster((dir / "rot.tif").string(), {{&a, nullptr, "h", "m"}}, rotated, {});
    try {
        readRasterBand((dir / "rot.tif").string());
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("rotated or sheared"), std::string::npos) << e.what();
    }
    GeoReference noCrs;
    noCrs.geoTransform = {0, 30, 0, 0, 0, -30};
    writeRaster((dir / "nocrs.tif").string(), {{&a, nullptr, "h", "m"}}, noCrs, {});
    try {
        readRasterBand((dir / "nocrs.tif").string());
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no coordinate reference system"), std::string::npos)
            << e.what();
    }
}

TEST(LoadDem, RefusesAllNodata) {
    const fs::path dir = scratchDir("allnodata");
    Grid<float> a(3, 3, std::numeric_limits<float>::quiet_NaN());
    GeoReference ref;
    ref.geoTransform = {350000, 30, 0, 3800000, 0, -30};
    ref.crsWkt = kUtmWkt;
    writeRaster((dir / "nan.tif").string(), {{&a, nullptr, "h", "m"}}, ref, {});
    EXPECT_THROW(loadDem((dir / "nan.tif").string()), Error);
}

// ---- Float32 tiles encoded by demlight (demlight/geo/tiff_tiles.h) ----------------------------------------

// TIFF Technical Note 3 by hand: 1.0f = 3F800000, -2.0f = C0000000. The bytes regrouped most
// significant first are 3F C0 80 00 00 00 00 00; each minus the one before it (mod 256).
TEST(TileEncoder, PredictorRegroupsBytesAndTakesDifferences) {
    const float row[2] = {1.0f, -2.0f};
    std::uint8_t out[8];
    detail::predictFloatRow(row, 2, out);
    const std::uint8_t expected[8] = {0x3F, 0x81, 0xC0, 0x80, 0x00, 0x00, 0x00, 0x00};
    EXPECT_EQ(0, std::memcmp(out, expected, 8));
}

// libtiff's horDiff16: 1, -1 (FFFF), 32767 (7FFF), -32768 (8000) give 0001, FFFE, 8000, 0001,
// stored little-endian.
TEST(TileEncoder, Int16PredictorTakesDifferencesModulo65536) {
    const std::int16_t row[4] = {1, -1, 32767, -32768};
    std::uint8_t out[8];
    detail::predictInt16Row(row, 4, out);
    const std::uint8_t expected[8] = {0x01, 0x00, 0xFE, 0xFF, 0x00, 0x80, 0x01, 0x00};
    EXPECT_EQ(0, std::memcmp(out, expected, 8));
}

TEST(TileEncoder, OnlyTheDefaultLayoutIsEncodedByDemlight) {
    const std::vector<std::string> defaults = {"TILED=YES",       "COMPRESS=ZSTD",        "ZSTD_LEVEL=1",
                                               "PREDICTOR=3",     "INTERLEAVE=BAND",      "NUM_THREADS=ALL_CPUS",
                                               "BIGTIFF=IF_SAFER"};
    const auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> co = defaults;
        co.insert(co.end(), extra.begin(), extra.end());
        return detail::tileEncoding(co);
    };
    ASSERT_TRUE(with({}).has_value());
    EXPECT_EQ(with({})->zstdLevel, 1);
    EXPECT_EQ(with({})->threads, 0);
    EXPECT_EQ(with({"ZSTD_LEVEL=7"})->zstdLevel, 7);
    EXPECT_EQ(with({"NUM_THREADS=1"})->threads, 1);
    EXPECT_TRUE(with({"BLOCKXSIZE=128", "BLOCKYSIZE=64"}).has_value());
    for (const std::string other : {"COMPRESS=DEFLATE", "PREDICTOR=1", "INTERLEAVE=PIXEL", "TILED=NO", "ZSTD_LEVEL=0",
                                    "NUM_THREADS=two", "DISCARD_LSB=4", "SPARSE_OK=FALSE"}) {
        SCOPED_TRACE(other);
        EXPECT_FALSE(with({other}).has_value());
    }
    // Int16 (fixed point) with its own predictor, 2, and not with the floats' 3.
    std::vector<std::string> int16 = defaults;
    int16[3] = "PREDICTOR=2";
    ASSERT_TRUE(detail::tileEncoding(int16, detail::TileSamples::Int16).has_value());
    EXPECT_EQ(detail::tileEncoding(int16, detail::TileSamples::Int16)->samples, detail::TileSamples::Int16);
    EXPECT_FALSE(detail::tileEncoding(int16, detail::TileSamples::Float32).has_value());
    EXPECT_FALSE(detail::tileEncoding(defaults, detail::TileSamples::Int16).has_value());
}

/// Float32 rasters of awkward sizes and values, written with demlight's tile encoder and with
/// GDAL's (libtiff's predictor and ZSTD), read back through GDAL: the same bits in every band,
/// the same descriptions, units and nodata.
TEST(TileEncoder, FilesDecodeToTheBitsGdalWrites) {
    const fs::path dir = scratchDir("floattiles");
    std::mt19937 rng(7);
    const auto bandOf = [&](std::size_t w, std::size_t h, int kind) {
        Grid<float> g(w, h);
        std::uniform_real_distribution<float> u(-500.0f, 4000.0f);
        for (std::size_t k = 0; k < g.size(); ++k) {
            float v = kind == 0 ? u(rng) : static_cast<float>(std::sin(0.01 * static_cast<double>(k)));
            switch (k % 97) {
                case 3: v = std::numeric_limits<float>::quiet_NaN(); break;
                case 5: v = std::numeric_limits<float>::infinity(); break;
                case 7: v = -std::numeric_limits<float>::infinity(); break;
                case 11: v = -0.0f; break;
                case 13: v = std::numeric_limits<float>::denorm_min(); break;
                case 17: v = std::numeric_limits<float>::max(); break;
                case 19: {
                    const std::uint32_t bits = static_cast<std::uint32_t>(rng());
                    std::memcpy(&v, &bits, 4);  // any bits, other NaN payloads included
                    break;
                }
                default: break;
            }
            g.data()[k] = v;
        }
        return g;
    };
    GeoReference ref;
    ref.geoTransform = {350000, 30, 0, 3800000, 0, -30};
    ref.crsWkt = kUtmWkt;
    struct Case {
        std::size_t w, h;
        std::vector<std::string> co;
        double nodata;
        bool ownTiles;       // demlight's encoder takes these options
        bool fixed = false;  // Int16 fixed point (two bands, no mask)
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Case> cases = {
        {300, 517, {}, nan, true},                                  // partial tiles on both edges
        {256, 512, {}, -9999.0, true},                              // whole tiles, NaN written as nodata
        {1, 1, {}, nan, true},                                      // one cell
        {700, 300, {"BLOCKXSIZE=128", "BLOCKYSIZE=64"}, nan, true},  // other tiles
        {513, 257, {"ZSTD_LEVEL=9", "NUM_THREADS=1"}, nan, true},
        {300, 517, {"BIGTIFF=YES"}, nan, true},  // 64-bit tile offsets
        {300, 200, {"PREDICTOR=1"}, nan, false},  // GDAL's, both times
        {300, 517, {}, nan, true, true},            // Int16 with the horizontal predictor
        {513, 257, {"BLOCKXSIZE=128", "BLOCKYSIZE=64", "NUM_THREADS=1"}, nan, true, true},
        {300, 200, {"PREDICTOR=1"}, nan, false, true},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(std::to_string(c.w) + "x" + std::to_string(c.h) + " " +
                     (c.co.empty() ? std::string("defaults") : c.co.front()));
        const Grid<float> a = bandOf(c.w, c.h, 0), b = bandOf(c.w, c.h, 1);
        Grid<std::uint8_t> mask(c.w, c.h, 0);
        for (std::size_t k = 0; k < mask.size(); k += 3) mask.data()[k] = 1;
        std::vector<OutputBand> bands = {{&a, nullptr, "first", "m"}, {&b, nullptr, "second", "deg"}};
        if (!c.fixed) bands.push_back({nullptr, &mask, "flag", ""});
        WriteOptions opt;
        opt.creationOptions = c.co;
        opt.nodata = c.nodata;
        if (c.fixed) opt.fixedPoint = FixedPoint16{4500.0 / 32767.0, 0.0};
        const std::string own = (dir / "own.tif").string(), gdal = (dir / "gdal.tif").string();
        const std::size_t before = detail::tilesWritten;
        writeRaster(own, bands, ref, opt);
        EXPECT_EQ(detail::tilesWritten > before, c.ownTiles);
        detail::encodeTiles = false;
        writeRaster(gdal, bands, ref, opt);
        detail::encodeTiles = true;

        RasterSummary sOwn, sGdal;
        const std::vector<Grid<float>> vOwn = readRasterBands(own, &sOwn), vGdal = readRasterBands(gdal, &sGdal);
        ASSERT_EQ(vOwn.size(), bands.size());
        ASSERT_EQ(vGdal.size(), bands.size());
        for (std::size_t i = 0; i < bands.size(); ++i) {
            ASSERT_EQ(vOwn[i].size(), vGdal[i].size());
            EXPECT_EQ(0, std::memcmp(vOwn[i].data(), vGdal[i].data(), vOwn[i].size() * sizeof(float))) << "band " << i;
        }
        // And the values given (readRasterBands turns nodata into NaN; fixed point comes back as
        // the stored integers, within half a step of the value over the scale).
        for (std::size_t k = 0; k < a.size(); ++k) {
            if (c.fixed) {
                const double scale = opt.fixedPoint->scale;
                const float given = a.data()[k], back = vOwn[0].data()[k];
                if (std::isnan(given)) {
                    ASSERT_TRUE(std::isnan(back)) << k;
                } else if (std::abs(given) < 4000.0f) {
                    ASSERT_NEAR(back * scale, given, 0.5 * scale + 1e-3) << k;
                }
                continue;
            }
            const float given = a.data()[k], back = vOwn[0].data()[k];
            if (std::isnan(given)) {
                ASSERT_TRUE(std::isnan(back)) << k;
            } else {
                ASSERT_EQ(0, std::memcmp(&given, &back, 4)) << k;
            }
        }
        EXPECT_EQ(sOwn.descriptions, sGdal.descriptions);
        EXPECT_EQ(sOwn.units, sGdal.units);
        EXPECT_EQ(sOwn.dataTypes, sGdal.dataTypes);
        EXPECT_EQ(sOwn.nodata.has_value(), sGdal.nodata.has_value());
        if (sOwn.nodata && sGdal.nodata && !std::isnan(*sGdal.nodata)) {
            EXPECT_EQ(*sOwn.nodata, *sGdal.nodata);
        }
        EXPECT_EQ(sOwn.imageStructure, sGdal.imageStructure);
        EXPECT_EQ(sOwn.ref.geoTransform, sGdal.ref.geoTransform);
        EXPECT_EQ(sOwn.ref.crsWkt, sGdal.ref.crsWkt);
        // Nothing but the two outputs in the folder (no temporary file).
        EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
    }
}

}  // namespace
}  // namespace demlight
