#include "demlight/geo/raster.h"

#include "demlight/geo/gdal_session.h"
#include "demlight/geo/output_file.h"
#include "demlight/geo/tiff_tiles.h"
#include "demlight/core/error.h"

#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <gdalwarper.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <strings.h>
#include <tuple>
#include <unistd.h>
#include <utility>

namespace demlight {
namespace {

namespace fs = std::filesystem;

struct DatasetCloser {
    void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

std::string withGdalReason(std::string message) {
    const std::string reason = detail::takeGdalError();
    if (!reason.empty()) message += " (" + reason + ")";
    return message;
}

/// GDAL virtual file systems (/vsizip/, /vsigzip/, /vsicurl/, ...): paths std::filesystem cannot see.
bool isGdalVirtualPath(const std::string& path) { return path.starts_with("/vsi"); }

/// A band (or overview) as float, NaN where it holds the nodata value `nodataFrom` declares.
Grid<float> readFloatBand(GDALRasterBand* band, GDALRasterBand* nodataFrom, const std::string& what) {
    const auto width = static_cast<std::size_t>(band->GetXSize());
    const auto height = static_cast<std::size_t>(band->GetYSize());
    Grid<float> g(width, height);
    if (band->RasterIO(GF_Read, 0, 0, static_cast<int>(width), static_cast<int>(height), g.data(),
                       static_cast<int>(width), static_cast<int>(height), GDT_Float32, 0, 0) != CE_None)
        throw Error(withGdalReason("cannot read " + what));
    int hasNodata = 0;
    const auto nodata = static_cast<float>(nodataFrom->GetNoDataValue(&hasNodata));
    if (hasNodata)
        for (float& v : g.values())
            if (v == nodata) v = std::numeric_limits<float>::quiet_NaN();
    return g;
}

/// Georeference, metadata and every band's description, unit and nodata of a dataset being
/// written, before any cells: the GTiff writes its directory with the first tile, and what
/// comes later would rewrite it. Byte bands declare the nodata value only when it fits.
void describeDataset(GDALDataset& ds, const GeoReference& ref, const WriteOptions& options,
                     const std::vector<OutputBand>& bands, GDALDataType type) {
    std::array<double, 6> gt = ref.geoTransform;
    ds.SetGeoTransform(gt.data());
    OGRSpatialReference srs;
    if (!ref.crsWkt.empty() && srs.importFromWkt(ref.crsWkt.c_str()) == OGRERR_NONE) ds.SetSpatialRef(&srs);
    for (const auto& [key, value] : options.metadata) ds.SetMetadataItem(key.c_str(), value.c_str());
    // GDAL makes three or four Byte bands an RGB(A) picture: QGIS would draw a 4-direction
    // truncation mask in colour, its 4th band as transparency. The bands are values.
    if (bands.size() >= 3 && ds.GetRasterBand(1)->GetColorInterpretation() != GCI_GrayIndex)
        for (std::size_t i = 0; i < bands.size(); ++i)
            ds.GetRasterBand(static_cast<int>(i) + 1)->SetColorInterpretation(i == 0 ? GCI_GrayIndex : GCI_Undefined);
    for (std::size_t i = 0; i < bands.size(); ++i) {
        GDALRasterBand* out = ds.GetRasterBand(static_cast<int>(i) + 1);
        out->SetDescription(bands[i].description.c_str());
        if (!bands[i].unit.empty()) out->SetUnitType(bands[i].unit.c_str());
        if (type == GDT_Int16) {
            out->SetNoDataValue(options.fixedPoint->nodata);
            out->SetScale(options.fixedPoint->scale);
            out->SetOffset(options.fixedPoint->offset);
        } else if (type == GDT_Float32 || (options.nodata >= 0 && options.nodata <= 255)) {
            out->SetNoDataValue(options.nodata);
        }
    }
}

/// The stored type of a raster's bands (TIFF needs one for all): Byte when every band is a mask,
/// else Float32, or Int16 with WriteOptions::fixedPoint.
GDALDataType storedType(const std::vector<OutputBand>& bands, const WriteOptions& options) {
    if (std::all_of(bands.begin(), bands.end(), [](const OutputBand& b) { return b.values == nullptr; })) return GDT_Byte;
    return options.fixedPoint ? GDT_Int16 : GDT_Float32;
}

/// `count` cells of a Float32 band from cell `first` in 16-bit fixed point (FixedPoint16).
const std::int16_t* fixedCells(const OutputBand& b, std::size_t first, std::size_t count, const FixedPoint16& fixed,
                               std::vector<std::int16_t>& buffer) {
    buffer.resize(count);
    const float* v = b.values->data() + first;
    const double limit = kFixedPoint16Max;
    for (std::size_t i = 0; i < count; ++i)
        buffer[i] = std::isnan(v[i]) ? fixed.nodata
                                     : static_cast<std::int16_t>(std::lround(
                                           std::clamp((static_cast<double>(v[i]) - fixed.offset) / fixed.scale, -limit, limit)));
    return buffer.data();
}

/// `count` cells of a band from cell `first` as Float32 to write: the band's own values when
/// they need no change (no copy), else converted through `buffer` (a mask widened, NaN replaced
/// by the nodata value).
const float* floatCells(const OutputBand& b, std::size_t first, std::size_t count, bool replaceNan, float nodata,
                        std::vector<float>& buffer) {
    if (b.values && !replaceNan) return b.values->data() + first;
    buffer.resize(count);
    if (b.values) {
        std::copy_n(b.values->data() + first, count, buffer.begin());
    } else {
        std::copy_n(b.mask->data() + first, count, buffer.begin());
    }
    if (replaceNan)
        for (float& v : buffer)
            if (std::isnan(v)) v = nodata;
    return buffer.data();
}

DatasetPtr openRaster(const std::string& path) {
    detail::ensureGdal();
    std::error_code ec;
    const bool onDisk = fs::exists(path, ec);
    if (onDisk && fs::is_directory(path, ec)) throw Error("cannot open '" + path + "': it is a directory");
    // A path std::filesystem does not see may still be one GDAL opens (a virtual file system, a
    // driver's connection string): GDAL decides, and only its failure is reported.
    detail::takeGdalError();
    DatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) {
        VSIStatBufL stat;
        if (!onDisk && (!isGdalVirtualPath(path) || VSIStatL(path.c_str(), &stat) != 0)) {
            detail::takeGdalError();
            throw Error("cannot open '" + path + "': no such file");
        }
        throw Error(withGdalReason("cannot open '" + path + "' as a raster: GDAL does not recognise it"));
    }
    if (ds->GetRasterCount() < 1) throw Error("'" + path + "' has no raster bands");
    return ds;
}

GeoReference readGeoReference(GDALDataset& ds, const std::string& path) {
    GeoReference ref;
    if (ds.GetGeoTransform(ref.geoTransform.data()) != CE_None)
        throw Error("'" + path + "' has no geotransform: demlight reads only georeferenced rasters");
    const auto& gt = ref.geoTransform;
    if (gt[2] != 0.0 || gt[4] != 0.0)
        throw Error("'" + path + "' has a rotated or sheared geotransform (terms " +
                    std::to_string(gt[2]) + ", " + std::to_string(gt[4]) +
                    "); warp it north-up first, e.g. gdalwarp in.tif out.tif");
    if (!(gt[1] > 0.0) || !(gt[5] < 0.0))
        throw Error("'" + path + "' is not north-up (pixel size " + std::to_string(gt[1]) + " x " +
                    std::to_string(gt[5]) + "); warp it north-up first with gdalwarp");
    const OGRSpatialReference* srs = ds.GetSpatialRef();
    if (!srs || srs->IsEmpty())
        throw Error("'" + path + "' has no coordinate reference system; assign one, e.g. "
                    "gdal_edit.py -a_srs EPSG:XXXX '" + path + "'");
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2018", nullptr};
    srs->exportToWkt(&wkt, options);
    ref.crsWkt = wkt ? wkt : "";
    CPLFree(wkt);
    return ref;
}

/// Rows per RasterIO call when writing: a multiple of the GTiff tile height (256), so each call
/// completes a row of tiles.
constexpr std::size_t kWriteStripRows = 256;

/// GDAL default creation options per driver; user options override by key.
std::vector<std::string> creationOptions(const WriteOptions& options, GDALDataType type) {
    std::vector<std::string> defaults;
    const bool floatData = type == GDT_Float32;
    if (options.format == "COG") {
        // Fixed-point horizons are smooth integers: the horizontal-difference predictor helps.
        defaults = {"COMPRESS=DEFLATE", type == GDT_Byte ? "PREDICTOR=NO" : "PREDICTOR=YES",
                    "NUM_THREADS=ALL_CPUS", "BIGTIFF=IF_SAFER"};
    } else if (options.format == "GTiff") {
        // ZSTD level 1 with the predictor compresses Float32 lightmaps as well as DEFLATE level 6
        // (within 3 %) at a third of the time; band-interleaved so each band is written, tiled
        // and compressed once, whatever the raster's size (GDAL's block cache never holds it).
        // Byte bands are masks and flags: differences of categories compress worse than the
        // categories (a 16-band truncation mask: 115 against 60 kB) and cost libtiff's byte loop.
        const char* predictor = floatData ? "PREDICTOR=3" : type == GDT_Byte ? "PREDICTOR=1" : "PREDICTOR=2";
        defaults = {"TILED=YES", "COMPRESS=ZSTD", "ZSTD_LEVEL=1", predictor,
                    "INTERLEAVE=BAND", "NUM_THREADS=ALL_CPUS", "BIGTIFF=IF_SAFER"};
    }
    auto key = [](const std::string& kv) { return kv.substr(0, kv.find('=')); };
    for (const auto& user : options.creationOptions) {
        if (user.find('=') == std::string::npos || user.front() == '=')
            throw Error("creation option '" + user + "' is not KEY=VALUE (-co)");
        std::erase_if(defaults, [&](const std::string& d) {
            return strcasecmp(key(d).c_str(), key(user).c_str()) == 0;
        });
        defaults.push_back(user);
    }
    return defaults;
}

/// The user's -co options against the driver's option list (GDALValidateCreationOptions), so a
/// misspelt key or value is an error instead of a silently different file, and block sizes
/// against what a writer can hold.
void validateUserCreationOptions(GDALDriver* driver, const WriteOptions& options) {
    if (options.creationOptions.empty()) return;
    for (const auto& kv : options.creationOptions)
        if (const std::string problem = blockSizeProblem(kv); !problem.empty())
            throw Error("invalid creation option for " + options.format + ": " + problem);
    CPLStringList list;
    for (const auto& kv : options.creationOptions) list.AddString(kv.c_str());
    std::string messages;
    CPLPushErrorHandlerEx(
        [](CPLErr, CPLErrorNum, const char* message) {
            auto* out = static_cast<std::string*>(CPLGetErrorHandlerUserData());
            if (!message) return;
            if (!out->empty()) *out += "; ";
            *out += message;
        },
        &messages);
    const int ok = GDALValidateCreationOptions(driver, list.List());
    CPLPopErrorHandler();
    if (!ok)
        throw Error("invalid creation option for " + options.format + ": " + messages +
                    " (gdalinfo --format " + options.format + " lists them)");
}

/// The GDAL driver of options.format (GTiff or COG), the user's creation options checked
/// against it: what every write to a new file checks first.
GDALDriver* checkedDriver(const WriteOptions& options) {
    if (options.format != "GTiff" && options.format != "COG")
        throw Error("output format '" + options.format + "' is not supported (-of GTiff or COG)");
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options.format.c_str());
    if (!driver) throw Error("GDAL has no '" + options.format + "' driver");
    validateUserCreationOptions(driver, options);
    return driver;
}

}  // namespace

namespace {

/// Band 1 of an open dataset: everything but the values.
RasterBand bandHeader(GDALDataset& ds, const std::string& path) {
    RasterBand out;
    out.path = path;
    out.ref = readGeoReference(ds, path);
    GDALRasterBand* band = ds.GetRasterBand(1);
    if (GDALDataTypeIsComplex(band->GetRasterDataType()))
        throw Error("'" + path + "' holds complex numbers (" + GDALGetDataTypeName(band->GetRasterDataType()) +
                    "), not heights or values: GDAL would read their real parts");
    out.width = static_cast<std::size_t>(ds.GetRasterXSize());
    out.height = static_cast<std::size_t>(ds.GetRasterYSize());
    out.scale = band->GetScale();
    out.offset = band->GetOffset();
    if (const char* unit = band->GetUnitType()) out.unit = unit;
    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    if (hasNodata) out.nodata = nodata;
    return out;
}

/// Band 1's values in `w`, nodata (and +-inf) as NaN; returns how many cells are nodata.
std::size_t readBandWindow(GDALDataset& ds, const RasterBand& header, const CellWindow& w, Grid<float>& values) {
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    values = Grid<float>(cols, rows);
    if (ds.GetRasterBand(1)->RasterIO(GF_Read, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                      static_cast<int>(rows), values.data(), static_cast<int>(cols),
                                      static_cast<int>(rows), GDT_Float32, 0, 0) != CE_None)
        throw Error(withGdalReason("cannot read the heights of '" + header.path + "'"));
    // Compare in float: integer nodata (-32768, 65535) converts exactly; a Float32 nodata such
    // as -3.4e38 must be compared after the same rounding the values went through.
    const bool hasNodata = header.nodata.has_value();
    const float nodataF = hasNodata ? static_cast<float>(*header.nodata) : 0.0f;
    const bool nodataIsNan = hasNodata && std::isnan(*header.nodata);
    std::size_t count = 0;
    for (float& v : values.values()) {
        if (std::isnan(v) || (hasNodata && !nodataIsNan && v == nodataF)) {
            v = std::numeric_limits<float>::quiet_NaN();
            ++count;
        } else if (!std::isfinite(v)) {
            v = std::numeric_limits<float>::quiet_NaN();  // +-inf heights are treated as nodata
            ++count;
        }
    }
    // A mask other than the nodata value marks its 0 cells as nodata, as GDAL's readers do: an
    // internal or .msk mask (gdal_translate -mask), an alpha band (gdalwarp -dstalpha). GDAL
    // makes only Byte and UInt16 alpha bands a mask; QGIS draws any alpha band as transparency,
    // and gdalwarp -dstalpha on an Int16 DEM writes an Int16 one, so any band whose colour
    // interpretation is alpha counts. Read as heights, masked cells would be terrain at whatever
    // value they hold (often 0 m: cliffs at the mask's edge).
    GDALRasterBand* band = ds.GetRasterBand(1);
    GDALRasterBand* mask = nullptr;
    if (!(band->GetMaskFlags() & (GMF_ALL_VALID | GMF_NODATA))) {
        mask = band->GetMaskBand();
    } else {
        for (int b = 2; b <= ds.GetRasterCount() && !mask; ++b)
            if (ds.GetRasterBand(b)->GetColorInterpretation() == GCI_AlphaBand) mask = ds.GetRasterBand(b);
    }
    if (mask) {
        std::vector<float> m(cols * rows);
        if (mask->RasterIO(GF_Read, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                           static_cast<int>(rows), m.data(), static_cast<int>(cols), static_cast<int>(rows),
                           GDT_Float32, 0, 0) != CE_None)
            throw Error(withGdalReason("cannot read the mask of '" + header.path + "'"));
        std::vector<float>& v = values.values();
        for (std::size_t i = 0; i < m.size(); ++i)
            if (m[i] == 0 && !std::isnan(v[i])) {
                v[i] = std::numeric_limits<float>::quiet_NaN();
                ++count;
            }
    }
    return count;
}

}  // namespace

RasterBand readRasterBand(const std::string& path) {
    DatasetPtr ds = openRaster(path);
    RasterBand out = bandHeader(*ds, path);
    out.nodataCount = readBandWindow(*ds, out, {0, 0, out.width, out.height}, out.values);
    return out;
}

RasterBand readRasterHeader(const std::string& path) {
    DatasetPtr ds = openRaster(path);
    return bandHeader(*ds, path);
}

Grid<float> readRasterWindow(const std::string& path, const CellWindow& window, std::size_t* nodataCount) {
    DatasetPtr ds = openRaster(path);
    const RasterBand header = bandHeader(*ds, path);
    if (!(window.col0 < window.col1 && window.row0 < window.row1 && window.col1 <= header.width &&
          window.row1 <= header.height))
        throw Error("window outside the " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                    " raster '" + path + "'");
    Grid<float> values;
    const std::size_t count = readBandWindow(*ds, header, window, values);
    if (nodataCount) *nodataCount = count;
    return values;
}

MemoryRaster::MemoryRaster(const Grid<float>& values, const GeoReference& ref, std::optional<double> nodata) {
    detail::ensureGdal();
    static std::atomic<unsigned long> serial{0};
    path_ = "/vsimem/demlight-array-" + std::to_string(::getpid()) + "-" + std::to_string(serial++) + ".tif";
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    DatasetPtr ds(gtiff->Create(path_.c_str(), static_cast<int>(values.width()), static_cast<int>(values.height()), 1,
                                GDT_Float32, nullptr));
    if (!ds) throw Error(withGdalReason("cannot hold a " + std::to_string(values.width()) + " x " +
                                        std::to_string(values.height()) + " array in GDAL's memory"));
    std::array<double, 6> gt = ref.geoTransform;
    ds->SetGeoTransform(gt.data());
    OGRSpatialReference srs;
    if (!ref.crsWkt.empty()) {
        if (srs.SetFromUserInput(ref.crsWkt.c_str()) != OGRERR_NONE)
            throw Error(withGdalReason("CRS '" + ref.crsWkt.substr(0, 200) +
                                       "' is not one GDAL reads (WKT, a PROJ string, or AUTHORITY:CODE such as EPSG:32610)"));
        ds->SetSpatialRef(&srs);
    }
    detail::takeGdalError();  // a missing CRS is reported by the reader, as for a file
    GDALRasterBand* band = ds->GetRasterBand(1);
    if (nodata) band->SetNoDataValue(*nodata);
    if (band->RasterIO(GF_Write, 0, 0, static_cast<int>(values.width()), static_cast<int>(values.height()),
                       const_cast<float*>(values.data()), static_cast<int>(values.width()),
                       static_cast<int>(values.height()), GDT_Float32, 0, 0) != CE_None)
        throw Error(withGdalReason("cannot hold the array in GDAL's memory"));
}

MemoryRaster::~MemoryRaster() { VSIUnlink(path_.c_str()); }

std::vector<Grid<float>> readRasterBands(const std::string& path, RasterSummary* summary) {
    if (summary) *summary = inspectRaster(path);
    DatasetPtr ds = openRaster(path);
    std::vector<Grid<float>> out;
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
        GDALRasterBand* band = ds->GetRasterBand(b);
        out.push_back(readFloatBand(band, band, "band " + std::to_string(b) + " of '" + path + "'"));
    }
    return out;
}

PictureBand readPictureBand(const std::string& path, const std::string& band) {
    DatasetPtr ds = openRaster(path);
    PictureBand out;
    out.bandCount = static_cast<std::size_t>(ds->GetRasterCount());
    std::string names;
    int found = 0;
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
        const std::string description = ds->GetRasterBand(b)->GetDescription();
        names += (names.empty() ? "" : ", ") + std::to_string(b) + (description.empty() ? "" : " " + description);
        if (!found && (band == std::to_string(b) || (!description.empty() && band == description))) found = b;
    }
    if (!found)
        throw Error("'" + path + "' has no band '" + band + "'; its bands: " + (names.empty() ? "none" : names));
    GDALRasterBand* b = ds->GetRasterBand(found);
    out.index = found;
    out.description = b->GetDescription();
    out.unit = b->GetUnitType();
    out.values = readFloatBand(b, b, "band " + std::to_string(found) + " of '" + path + "'");
    int hasScale = 0, hasOffset = 0;
    const double scale = b->GetScale(&hasScale), offset = b->GetOffset(&hasOffset);
    if ((hasScale && scale != 1.0) || (hasOffset && offset != 0.0))
        for (float& v : out.values.values()) v = static_cast<float>(v * (hasScale ? scale : 1.0) + (hasOffset ? offset : 0.0));
    if (ds->GetGeoTransform(out.geoTransform.data()) != CE_None) out.geoTransform = {0, 1, 0, 0, 0, 1};
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) out.geographic = srs->IsGeographic();
    CSLConstList items = ds->GetMetadata(nullptr);
    for (CSLConstList it = items; it && *it; ++it) {
        char* key = nullptr;
        const char* value = CPLParseNameValue(*it, &key);
        if (key && value) out.metadata[key] = value;
        CPLFree(key);
    }
    return out;
}

std::vector<Grid<float>> readRasterOverview(const std::string& path, int level) {
    DatasetPtr ds = openRaster(path);
    std::vector<Grid<float>> out;
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
        GDALRasterBand* full = ds->GetRasterBand(b);
        GDALRasterBand* band = level >= 0 && level < full->GetOverviewCount() ? full->GetOverview(level) : nullptr;
        if (!band) throw Error("'" + path + "' has no overview " + std::to_string(level) + " of band " + std::to_string(b));
        out.push_back(readFloatBand(band, full, "overview " + std::to_string(level) + " of '" + path + "'"));
    }
    return out;
}

std::vector<Grid<float>> readRasterResampled(const std::string& path, const GeoReference& target,
                                             std::size_t width, std::size_t height) {
    DatasetPtr src = openRaster(path);
    const GeoReference srcRef = readGeoReference(*src, path);
    const int bands = src->GetRasterCount();

    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    DatasetPtr dst(mem->Create("", static_cast<int>(width), static_cast<int>(height), bands,
                               GDT_Float32, nullptr));
    std::array<double, 6> gt = target.geoTransform;
    dst->SetGeoTransform(gt.data());
    OGRSpatialReference dstSrs;
    dstSrs.importFromWkt(target.crsWkt.c_str());
    dst->SetSpatialRef(&dstSrs);
    for (int b = 1; b <= bands; ++b) {
        dst->GetRasterBand(b)->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
        dst->GetRasterBand(b)->Fill(std::numeric_limits<double>::quiet_NaN());
    }
    if (GDALReprojectImage(GDALDataset::ToHandle(src.get()), srcRef.crsWkt.c_str(),
                           GDALDataset::ToHandle(dst.get()), target.crsWkt.c_str(),
                           GRA_Bilinear, 0.0, 0.125, nullptr, nullptr, nullptr) != CE_None)
        throw Error(withGdalReason("cannot resample '" + path + "' onto the DEM grid"));

    std::vector<Grid<float>> out;
    for (int b = 1; b <= bands; ++b) {
        Grid<float> g(width, height);
        if (dst->GetRasterBand(b)->RasterIO(GF_Read, 0, 0, static_cast<int>(width),
                                            static_cast<int>(height), g.data(),
                                            static_cast<int>(width), static_cast<int>(height),
                                            GDT_Float32, 0, 0) != CE_None)
            throw Error(withGdalReason("cannot resample '" + path + "'"));
        out.push_back(std::move(g));
    }
    return out;
}

RasterSummary inspectRaster(const std::string& path) {
    DatasetPtr ds = openRaster(path);
    RasterSummary s;
    s.driver = ds->GetDriver() ? ds->GetDriver()->GetDescription() : "";
    s.width = static_cast<std::size_t>(ds->GetRasterXSize());
    s.height = static_cast<std::size_t>(ds->GetRasterYSize());
    ds->GetGeoTransform(s.ref.geoTransform.data());
    if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
        char* wkt = nullptr;
        srs->exportToWkt(&wkt);
        s.ref.crsWkt = wkt ? wkt : "";
        CPLFree(wkt);
    }
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
        GDALRasterBand* band = ds->GetRasterBand(b);
        s.descriptions.emplace_back(band->GetDescription());
        s.units.emplace_back(band->GetUnitType());
        s.dataTypes.emplace_back(GDALGetDataTypeName(band->GetRasterDataType()));
    }
    int hasNodata = 0;
    const double nodata = ds->GetRasterBand(1)->GetNoDataValue(&hasNodata);
    if (hasNodata) s.nodata = nodata;
    s.overviews = static_cast<std::size_t>(ds->GetRasterBand(1)->GetOverviewCount());
    const auto readDomain = [&](const char* domain, std::map<std::string, std::string>& out) {
        CSLConstList items = ds->GetMetadata(domain);
        for (CSLConstList it = items; it && *it; ++it) {
            char* key = nullptr;
            const char* value = CPLParseNameValue(*it, &key);
            if (key && value) out[key] = value;
            CPLFree(key);
        }
    };
    readDomain(nullptr, s.metadata);
    readDomain("IMAGE_STRUCTURE", s.imageStructure);
    return s;
}

namespace {

/// Forwards the writer's progress to WriteOptions::progress and remembers a request to stop;
/// gdalCallback lets GDAL's long steps (overviews, the COG copy) ask it too.
class WriteProgress {
public:
    explicit WriteProgress(const ProgressFn& fn) : fn_(fn) {}
    /// False once the caller asked to stop.
    bool report(double fraction) {
        if (fn_ && !stopped_ && !fn_(std::clamp(fraction, 0.0, 1.0), "write")) stopped_ = true;
        return !stopped_;
    }
    bool stopped() const { return stopped_; }
    /// A GDALProgressFunc over [from, to] of the whole write; its data is a Span.
    struct Span {
        WriteProgress* progress;
        double from, to;
    };
    static int CPL_STDCALL gdalCallback(double fraction, const char*, void* data) {
        const auto* span = static_cast<const Span*>(data);
        return span->progress->report(span->from + fraction * (span->to - span->from)) ? TRUE : FALSE;
    }

private:
    const ProgressFn& fn_;
    bool stopped_ = false;
};

/// A creation option's value (case-insensitive key), or null.
const char* findOption(const std::vector<std::string>& options, const char* key) {
    const std::size_t n = std::strlen(key);
    for (const auto& kv : options)
        if (kv.size() > n && kv[n] == '=' && strncasecmp(kv.c_str(), key, n) == 0) return kv.c_str() + n + 1;
    return nullptr;
}

/// Whether the user's -co options choose the COG's overviews themselves (one method for every
/// band, none, or a reprojection, which drops the source's overviews): then GDAL builds them.
bool overviewsChosenByUser(const WriteOptions& options) {
    for (const char* key : {"RESAMPLING", "OVERVIEW_RESAMPLING", "WARP_RESAMPLING", "TILING_SCHEME", "TARGET_SRS"})
        if (findOption(options.creationOptions, key)) return true;
    const char* overviews = findOption(options.creationOptions, "OVERVIEWS");
    return overviews && (strcasecmp(overviews, "NONE") == 0 || strcasecmp(overviews, "IGNORE_EXISTING") == 0);
}

/// The overview factors GDAL's COG driver would make: halve until both sides fit in one tile
/// (BLOCKSIZE, 512 by default), or OVERVIEW_COUNT levels when given.
std::vector<int> cogOverviewFactors(std::size_t width, std::size_t height, const WriteOptions& options) {
    const char* block = findOption(options.creationOptions, "BLOCKSIZE");
    const std::size_t tile = block ? static_cast<std::size_t>(std::max(1, std::atoi(block))) : 512;
    const char* countOption = findOption(options.creationOptions, "OVERVIEW_COUNT");
    const int count = countOption ? std::atoi(countOption) : -1;
    std::vector<int> factors;
    std::size_t w = width, h = height;
    for (int factor = 2;; factor *= 2) {
        if (count < 0 ? (w <= tile && h <= tile) : (static_cast<int>(factors.size()) == count || (w == 1 && h == 1)))
            break;
        w = std::max<std::size_t>(1, w / 2);
        h = std::max<std::size_t>(1, h / 2);
        factors.push_back(factor);
    }
    return factors;
}

/// Builds the overviews of an in-memory dataset band by band, each with its own method: the
/// levels are made empty for all bands at once (MEM builds only all bands alike), then each
/// band's are computed from its full-resolution cells.
CPLErr buildOverviewsPerBand(GDALDataset& ds, const std::vector<OutputBand>& bands, const std::vector<int>& factors,
                             WriteProgress& progress, double from, double to) {
    if (factors.empty()) return CE_None;
    if (ds.BuildOverviews("NONE", static_cast<int>(factors.size()), factors.data(), 0, nullptr, nullptr, nullptr,
                          nullptr) != CE_None)
        return CE_Failure;
    for (std::size_t i = 0; i < bands.size(); ++i) {
        GDALRasterBand* band = ds.GetRasterBand(static_cast<int>(i) + 1);
        std::vector<GDALRasterBandH> levels;
        for (int k = 0; k < band->GetOverviewCount(); ++k) levels.push_back(GDALRasterBand::ToHandle(band->GetOverview(k)));
        const double share = (to - from) / static_cast<double>(bands.size());
        WriteProgress::Span span{&progress, from + share * static_cast<double>(i), from + share * static_cast<double>(i + 1)};
        const char* method = bands[i].resampling == Resampling::Nearest ? "NEAREST" : "AVERAGE";
        if (GDALRegenerateOverviews(GDALRasterBand::ToHandle(band), static_cast<int>(levels.size()), levels.data(),
                                    method, WriteProgress::gdalCallback, &span) != CE_None)
            return CE_Failure;
    }
    return CE_None;
}

}  // namespace

void checkRasterPath(const std::string& path) {
    const std::string ext = fs::path(path).extension().string();
    if (!ext.empty() && strcasecmp(ext.c_str(), ".tif") != 0 && strcasecmp(ext.c_str(), ".tiff") != 0)
        throw Error("cannot write '" + path + "': its extension '" + ext +
                    "' names another format, and this output is a GeoTIFF; name it .tif or .tiff");
}

namespace {

/// The size all bands share (internal errors when one is empty or of another size).
std::pair<std::size_t, std::size_t> bandsShape(const std::string& path, const std::vector<OutputBand>& bands) {
    const auto shapeOf = [](const OutputBand& b) {
        return b.values ? std::pair(b.values->width(), b.values->height())
                        : std::pair(b.mask->width(), b.mask->height());
    };
    const auto shape = shapeOf(bands.front());
    for (const auto& b : bands) {
        if (!b.values && !b.mask) throw Error("internal: output band '" + b.description + "' is empty");
        if (shapeOf(b) != shape) throw Error("internal: output bands of '" + path + "' differ in size");
    }
    return shape;
}

/// One writeRaster(): the file is written under a temporary name in its own private folder and
/// renamed on success, so a failed or interrupted run never leaves a partial file at `path`.
/// GTiff is created directly and filled from the grids (its Float32 and Int16 tiles encoded by
/// detail::TileWriter, demlight/geo/tiff_tiles.h); COG can only be made by CreateCopy, so it is
/// staged in a MEM dataset first. (The COG driver's own scratch files go beside its output: into
/// the temporary file's private folder, removed with it.)
class RasterWrite {
public:
    RasterWrite(const std::string& path, const std::vector<OutputBand>& bands, const WriteOptions& options,
                GDALDataType type, const std::vector<std::string>& creationOptions)
        : path_(path), bands_(bands), options_(options), type_(type), co_(creationOptions), tmp_(path),
          direct_(options.format == "GTiff"), progress_(options.progress) {
        std::tie(width_, height_) = bandsShape(path, bands);
        for (const auto& kv : co_) coList_.AddString(kv.c_str());
    }

    void run(GDALDriver* driver, const GeoReference& ref) {
        // libtiff opens local files only, not GDAL's virtual ones.
        std::optional<detail::TileEncoding> ownTiles;
        if (direct_ && (type_ == GDT_Float32 || type_ == GDT_Int16) && detail::encodeTiles && !isGdalVirtualPath(path_))
            ownTiles = detail::tileEncoding(co_, type_ == GDT_Float32 ? detail::TileSamples::Float32
                                                                     : detail::TileSamples::Int16);
        if (ownTiles) coList_.AddString("SPARSE_OK=TRUE");
        detail::takeGdalError();
        create(driver, ref);
        if (ownTiles) openTiles(*ownTiles);
        fillBands();
        if (!direct_) copyToCog(driver);
        close();
        // A request to stop that comes now finds the file complete: it is kept.
        tmp_.commit();
    }

private:
    /// Ends the write: the datasets (or the tile writer) closed, every temporary file removed;
    /// Cancelled when the caller asked to stop, else an Error naming the cause, the tile writer's
    /// `reason` or GDAL's (thrown by std::rethrow_exception, so that a Cancelled keeps its type).
    std::exception_ptr fail(const std::string& what, std::string reason = {}) {
        ds_.reset();
        tiles_.reset();
        if (const std::string gdal = detail::takeGdalError(); reason.empty()) reason = gdal;
        if (progress_.stopped()) {
            tmp_.discard();
            return std::make_exception_ptr(Cancelled());
        }
        const std::string message =
            writeFailureMessage((what.empty() ? "" : what + " of ") + "'" + path_ + "'", tmp_.path(), reason);
        tmp_.discard();
        return std::make_exception_ptr(Error(message));
    }

    void create(GDALDriver* driver, const GeoReference& ref) {
        const int w = static_cast<int>(width_), h = static_cast<int>(height_), n = static_cast<int>(bands_.size());
        if (direct_) {
            ds_.reset(driver->Create(tmp_.path().c_str(), w, h, n, type_, coList_.List()));
            if (!ds_) std::rethrow_exception(fail({}));
        } else {
            ds_.reset(GetGDALDriverManager()->GetDriverByName("MEM")->Create("", w, h, n, type_, nullptr));
        }
        describeDataset(*ds_, ref, options_, bands_, type_);
    }

    /// Closes GDAL's file before any cell (GDAL writes the directory with every tile offset zero)
    /// and opens the tile writer on it.
    void openTiles(const detail::TileEncoding& encoding) {
        ds_.reset();
        if (const std::string closeError = detail::takeGdalError(); !closeError.empty())
            std::rethrow_exception(fail({}));
        try {
            tiles_.emplace(tmp_.path(), width_, height_, bands_.size(), encoding);
        } catch (const Error& e) {
            std::rethrow_exception(fail({}, e.what()));
        }
        // Four strips of whole tile rows per batch when they take at most 16 MB: a 1201-wide band
        // has five tiles a row, which two threads share unevenly one row at a time.
        const std::size_t tileH = tiles_->tileHeight();
        const std::size_t strip = tileH * std::max<std::size_t>(1, kWriteStripRows / tileH);
        constexpr std::size_t kBatchStrips = 4, kBatchBytes = std::size_t{16} << 20;
        stripRows_ = kBatchStrips * strip * width_ * sizeof(float) <= kBatchBytes ? kBatchStrips * strip : strip;
    }

    /// Each band in strips of whole tile rows, each flushed to the file before the next (the GTiff
    /// compresses and writes those tiles then, not all at the close): a full disk shows at the
    /// strip that meets it, and a request to stop is seen within a strip. A band that needs
    /// converting (a mask, or NaN to the nodata value) goes through a strip-sized buffer that stays
    /// in cache, not a copy of the whole band.
    void fillBands() {
        const std::size_t strips = (height_ + stripRows_ - 1) / stripRows_;
        for (std::size_t i = 0; i < bands_.size(); ++i) {
            for (std::size_t s = 0; s < strips; ++s) {
                // Shares of the whole write: GTiff's bands are all of it; a COG's staging is quick.
                const double done = static_cast<double>(i * strips + s) / static_cast<double>(bands_.size() * strips);
                if (!progress_.report(fillShare() * done)) std::rethrow_exception(fail({}));
                const std::size_t r0 = s * stripRows_;
                writeStrip(i, r0, std::min(stripRows_, height_ - r0));
            }
        }
    }

    void writeStrip(std::size_t i, std::size_t r0, std::size_t rows) {
        const OutputBand& b = bands_[i];
        const std::size_t first = r0 * width_, count = rows * width_;
        const bool replaceNan = !std::isnan(options_.nodata);
        const auto nodataF = static_cast<float>(options_.nodata);
        if (tiles_) {
            const void* data = type_ == GDT_Int16
                                   ? static_cast<const void*>(fixedCells(b, first, count, *options_.fixedPoint, fixed_))
                                   : floatCells(b, first, count, replaceNan, nodataF, buffer_);
            try {
                tiles_->writeRows(i, r0, rows, data);
            } catch (const Error& e) {
                std::rethrow_exception(fail("band " + std::to_string(i + 1), e.what()));
            }
            return;
        }
        void* data;
        if (type_ == GDT_Byte)
            data = const_cast<std::uint8_t*>(b.mask->rowPtr(r0));
        else if (type_ == GDT_Int16)
            data = const_cast<std::int16_t*>(fixedCells(b, first, count, *options_.fixedPoint, fixed_));
        else
            data = const_cast<float*>(floatCells(b, first, count, replaceNan, nodataF, buffer_));
        GDALRasterBand* out = ds_->GetRasterBand(static_cast<int>(i) + 1);
        const int w = static_cast<int>(width_), h = static_cast<int>(rows);
        CPLErr err = out->RasterIO(GF_Write, 0, static_cast<int>(r0), w, h, data, w, h, type_, 0, 0);
        if (err == CE_None && direct_) err = out->FlushCache(false);
        if (err != CE_None) std::rethrow_exception(fail("band " + std::to_string(i + 1)));
    }

    /// A COG's overviews (each band by its own method, unless the user chose them) and the
    /// compressed copy: most of its write.
    void copyToCog(GDALDriver* driver) {
        constexpr double kOverviewShare = 0.3;
        if (!overviewsChosenByUser(options_) &&
            buildOverviewsPerBand(*ds_, bands_, cogOverviewFactors(width_, height_, options_), progress_, fillShare(),
                                  fillShare() + kOverviewShare) != CE_None)
            std::rethrow_exception(fail("overviews"));
        WriteProgress::Span span{&progress_, fillShare() + kOverviewShare, 1.0};
        DatasetPtr cog(driver->CreateCopy(tmp_.path().c_str(), ds_.get(), FALSE, coList_.List(),
                                          WriteProgress::gdalCallback, &span));
        if (!cog) std::rethrow_exception(fail({}));
        ds_ = std::move(cog);
    }

    void close() {
        if (tiles_) {
            try {
                tiles_->close();
            } catch (const Error& e) {
                std::rethrow_exception(fail({}, e.what()));
            }
            return;
        }
        GDALClose(GDALDataset::ToHandle(ds_.release()));
        if (const std::string closeError = detail::takeGdalError(); !closeError.empty()) {
            const std::string message = writeFailureMessage("'" + path_ + "'", tmp_.path(), closeError);
            tmp_.discard();
            throw Error(message);
        }
    }

    double fillShare() const { return direct_ ? 1.0 : 0.1; }

    const std::string& path_;
    const std::vector<OutputBand>& bands_;
    const WriteOptions& options_;
    const GDALDataType type_;
    const std::vector<std::string>& co_;
    TemporaryFile tmp_;
    const bool direct_;
    WriteProgress progress_;
    std::size_t width_ = 0, height_ = 0;
    std::size_t stripRows_ = kWriteStripRows;
    CPLStringList coList_;
    DatasetPtr ds_;
    std::optional<detail::TileWriter> tiles_;
    std::vector<float> buffer_;
    std::vector<std::int16_t> fixed_;
};

}  // namespace

void writeRaster(const std::string& path, const std::vector<OutputBand>& bands,
                 const GeoReference& ref, const WriteOptions& options,
                 const std::string& inputPath) {
    detail::ensureGdal();
    if (bands.empty()) throw Error("nothing to write to '" + path + "'");
    GDALDriver* driver = checkedDriver(options);
    checkOutputFile(path);
    checkRasterPath(path);
    checkNotInput(path, inputPath);
    const GDALDataType type = storedType(bands, options);
    bandsShape(path, bands);
    const std::vector<std::string> co = creationOptions(options, type);
    RasterWrite(path, bands, options, type, co).run(driver, ref);
}

std::vector<std::string> rasterFiles(const std::string& path) {
    const DatasetPtr ds = openRaster(path);
    std::vector<std::string> out;
    char** files = ds->GetFileList();
    for (char** f = files; f && *f; ++f) out.emplace_back(*f);
    CSLDestroy(files);
    return out;
}

std::string blockSizeProblem(const std::string& option) {
    const std::size_t eq = option.find('=');
    if (eq == std::string::npos) return {};
    const std::string key = option.substr(0, eq), value = option.substr(eq + 1);
    if (strcasecmp(key.c_str(), "BLOCKXSIZE") != 0 && strcasecmp(key.c_str(), "BLOCKYSIZE") != 0 &&
        strcasecmp(key.c_str(), "BLOCKSIZE") != 0)
        return {};
    const std::string range = "a block side must be a whole number of cells from 1 to " +
                              std::to_string(kMaxBlockSideCells) + " (a block is held whole in memory)";
    const bool digits = !value.empty() && value.size() <= 18 &&
                        std::all_of(value.begin(), value.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
    if (!digits) return "'" + option + "': " + range;
    const long long side = std::stoll(value);
    if (side < 1 || side > kMaxBlockSideCells) return "'" + option + "': " + range;
    return {};
}

void checkCreationOptions(const std::string& format, const std::vector<std::string>& userOptions) {
    detail::ensureGdal();
    WriteOptions options;
    options.format = format;
    options.creationOptions = userOptions;
    checkedDriver(options);
    (void)creationOptions(options, GDT_Float32);  // throws on an option that is not KEY=VALUE
}

void copyRasterWithMetadata(const std::string& source, const std::string& path,
                            const std::map<std::string, std::string>& metadata) {
    detail::ensureGdal();
    checkOutputFile(path);
    checkRasterPath(path);
    TemporaryFile tmp(path);
    const auto fail = [&](const std::string& reason) {
        const std::string message = writeFailureMessage("'" + path + "'", tmp.path(), reason);
        tmp.discard();
        return Error(message);
    };
    std::error_code ec;
    fs::copy_file(source, tmp.path(), fs::copy_options::overwrite_existing, ec);
    if (ec) throw fail("copying '" + source + "': " + ec.message());
    detail::takeGdalError();
    static const char* const kGTiffOnly[] = {"GTiff", nullptr};
    DatasetPtr ds(GDALDataset::FromHandle(
        GDALOpenEx(tmp.path().c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE, kGTiffOnly, nullptr, nullptr)));
    if (!ds) throw fail(detail::takeGdalError());
    for (const auto& [key, value] : metadata) ds->SetMetadataItem(key.c_str(), value.c_str());
    GDALClose(GDALDataset::ToHandle(ds.release()));
    if (const std::string closeError = detail::takeGdalError(); !closeError.empty()) throw fail(closeError);
    tmp.commit();
}

struct RasterSink::State {
    std::string path;
    std::size_t width, height;
    GeoReference ref;
    WriteOptions options;
    /// GTiff: the file written, renamed onto `path` at commit. COG: a scratch GeoTIFF the
    /// windows stream into, copied to COG layout by writeRaster at commit.
    std::optional<TemporaryFile> file;
    DatasetPtr ds;
    std::vector<OutputBand> layout;  // the first window's bands: names, units, resampling
    bool masks = false;
};

RasterSink::RasterSink(std::string path, std::size_t width, std::size_t height, GeoReference ref,
                       WriteOptions options, const std::string& inputPath)
    : state_(std::make_unique<State>()) {
    detail::ensureGdal();
    if (options.format != "GTiff" && options.format != "COG")
        throw Error("output format '" + options.format + "' is not supported (-of GTiff or COG)");
    checkNotInput(path, inputPath);
    checkOutputFile(path);
    State& st = *state_;
    if (options.format == "COG") {
        st.file.emplace(path + ".stream.tif");  // never committed: copied to the COG at commit
    } else {
        st.file.emplace(path);
    }
    st.path = std::move(path);
    st.width = width;
    st.height = height;
    st.ref = std::move(ref);
    st.options = std::move(options);
}

RasterSink::~RasterSink() {
    if (!state_) return;
    state_->ds.reset();
    state_->file.reset();  // removes the file unless committed
}

void RasterSink::write(const CellWindow& w, const std::vector<OutputBand>& bands) {
    State& st = *state_;
    if (bands.empty()) throw Error("internal: nothing to write to '" + st.path + "'");
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    if (w.col1 > st.width || w.row1 > st.height || cols == 0 || rows == 0)
        throw Error("internal: window outside the output '" + st.path + "'");
    const GDALDataType type = storedType(bands, st.options);
    const bool allMasks = type == GDT_Byte;
    if (!st.ds) {
        // The streamed file: a tiled GeoTIFF (the COG layout needs the whole raster; it is made
        // from this file at commit).
        GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
        WriteOptions streamed = st.options;
        if (st.options.format == "COG") {
            streamed.format = "GTiff";
            streamed.creationOptions.clear();
        }
        validateUserCreationOptions(gtiff, streamed);
        CPLStringList co;
        for (const auto& kv : creationOptions(streamed, type)) co.AddString(kv.c_str());
        detail::takeGdalError();
        st.ds.reset(gtiff->Create(st.file->path().c_str(), static_cast<int>(st.width), static_cast<int>(st.height),
                                  static_cast<int>(bands.size()), type, co.List()));
        if (!st.ds)
            throw Error(writeFailureMessage("'" + st.path + "'", st.file->path(), detail::takeGdalError()));
        describeDataset(*st.ds, st.ref, st.options, bands, type);
        st.layout = bands;
        st.masks = allMasks;
    }
    if (bands.size() != st.layout.size()) throw Error("internal: windows of '" + st.path + "' differ in bands");
    const bool replaceNan = !std::isnan(st.options.nodata);
    const auto nodataF = static_cast<float>(st.options.nodata);
    std::vector<float> buffer;
    std::vector<std::int16_t> fixedBuffer;
    for (std::size_t i = 0; i < bands.size(); ++i) {
        const OutputBand& b = bands[i];
        GDALRasterBand* out = st.ds->GetRasterBand(static_cast<int>(i) + 1);
        CPLErr err;
        if (type == GDT_Byte) {
            err = out->RasterIO(GF_Write, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                static_cast<int>(rows), const_cast<std::uint8_t*>(b.mask->data()),
                                static_cast<int>(cols), static_cast<int>(rows), GDT_Byte, 0, 0);
        } else if (type == GDT_Int16) {
            const std::int16_t* data = fixedCells(b, 0, cols * rows, *st.options.fixedPoint, fixedBuffer);
            err = out->RasterIO(GF_Write, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                static_cast<int>(rows), const_cast<std::int16_t*>(data), static_cast<int>(cols),
                                static_cast<int>(rows), GDT_Int16, 0, 0);
        } else {
            const float* data = floatCells(b, 0, cols * rows, replaceNan, nodataF, buffer);
            err = out->RasterIO(GF_Write, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                static_cast<int>(rows), const_cast<float*>(data), static_cast<int>(cols),
                                static_cast<int>(rows), GDT_Float32, 0, 0);
        }
        if (err != CE_None)
            throw Error(writeFailureMessage("band " + std::to_string(i + 1) + " of '" + st.path + "'", st.file->path(),
                                            detail::takeGdalError()));
    }
}

void RasterSink::setMetadata(const std::string& key, const std::string& value) {
    State& st = *state_;
    if (!st.ds) throw Error("internal: metadata for '" + st.path + "' before its first window");
    st.options.metadata[key] = value;  // a COG is written from the options at commit
    st.ds->SetMetadataItem(key.c_str(), value.c_str());
}

void RasterSink::commit() {
    State& st = *state_;
    if (!st.ds) throw Error("internal: nothing was written to '" + st.path + "'");
    detail::takeGdalError();
    st.ds.reset();  // flushes the streamed file
    const std::string closeError = detail::takeGdalError();
    if (!closeError.empty()) throw Error(writeFailureMessage("'" + st.path + "'", st.file->path(), closeError));
    if (st.options.format != "COG") {
        st.file->commit();
        return;
    }
    // COG: the overviews and layout need the whole raster, read back from the streamed file and
    // written by writeRaster (band-wise overview resampling, its own temporaries).
    std::vector<Grid<float>> values = readRasterBands(st.file->path());
    // Fixed point is read back raw (nodata as NaN): to the band's values, which writeRaster
    // stores again as the same integers.
    if (st.options.fixedPoint && !st.masks)
        for (Grid<float>& g : values)
            for (float& v : g.values())
                v = static_cast<float>(v * st.options.fixedPoint->scale + st.options.fixedPoint->offset);
    std::vector<Grid<std::uint8_t>> masks;
    std::vector<OutputBand> bands = st.layout;
    for (std::size_t i = 0; i < bands.size(); ++i) {
        if (st.masks) {
            Grid<std::uint8_t> m(values[i].width(), values[i].height());
            for (std::size_t k = 0; k < m.size(); ++k) {
                const float v = values[i].data()[k];
                m.data()[k] = static_cast<std::uint8_t>(std::isnan(v) ? st.options.nodata : v);
            }
            masks.push_back(std::move(m));
        }
    }
    for (std::size_t i = 0; i < bands.size(); ++i) {
        bands[i].values = st.masks ? nullptr : &values[i];
        bands[i].mask = st.masks ? &masks[i] : nullptr;
    }
    writeRaster(st.path, bands, st.ref, st.options);
    st.file.reset();
}

void setRasterCacheBytes(double bytes) {
    detail::ensureGdal();
    GDALSetCacheMax64(static_cast<GIntBig>(std::max(bytes, 0.0)));
}

}  // namespace demlight
