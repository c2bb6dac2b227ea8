#include "geo/raster.h"

#include "geo/gdal_session.h"
#include "src/error.h"

#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <gdalwarper.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <unistd.h>

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
        throw Error("'" + path + "' has no geotransform: demlight needs a georeferenced DEM");
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
std::vector<std::string> creationOptions(const WriteOptions& options, bool floatData) {
    std::vector<std::string> defaults;
    if (options.format == "COG") {
        defaults = {"COMPRESS=DEFLATE", floatData ? "PREDICTOR=YES" : "PREDICTOR=NO",
                    "NUM_THREADS=ALL_CPUS", "BIGTIFF=IF_SAFER"};
    } else if (options.format == "GTiff") {
        // ZSTD level 1 with the predictor compresses Float32 lightmaps as well as DEFLATE level 6
        // (within 3 %) at a third of the time; band-interleaved so each band is written, tiled
        // and compressed once, whatever the raster's size (GDAL's block cache never holds it).
        defaults = {"TILED=YES", "COMPRESS=ZSTD", "ZSTD_LEVEL=1", floatData ? "PREDICTOR=3" : "PREDICTOR=2",
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
/// misspelt key or value is an error instead of a silently different file.
void validateUserCreationOptions(GDALDriver* driver, const WriteOptions& options) {
    if (options.creationOptions.empty()) return;
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

}  // namespace

RasterBand readRasterBand(const std::string& path) {
    DatasetPtr ds = openRaster(path);
    RasterBand out;
    out.path = path;
    out.ref = readGeoReference(*ds, path);

    GDALRasterBand* band = ds->GetRasterBand(1);
    const auto width = static_cast<std::size_t>(ds->GetRasterXSize());
    const auto height = static_cast<std::size_t>(ds->GetRasterYSize());
    out.values = Grid<float>(width, height);
    if (band->RasterIO(GF_Read, 0, 0, static_cast<int>(width), static_cast<int>(height),
                       out.values.data(), static_cast<int>(width), static_cast<int>(height),
                       GDT_Float32, 0, 0) != CE_None)
        throw Error(withGdalReason("cannot read the heights of '" + path + "'"));

    out.scale = band->GetScale();
    out.offset = band->GetOffset();
    if (const char* unit = band->GetUnitType()) out.unit = unit;

    int hasNodata = 0;
    const double nodata = band->GetNoDataValue(&hasNodata);
    if (hasNodata) out.nodata = nodata;
    // Compare in float: integer nodata (-32768, 65535) converts exactly; a Float32 nodata such
    // as -3.4e38 must be compared after the same rounding the values went through.
    const float nodataF = hasNodata ? static_cast<float>(nodata) : 0.0f;
    const bool nodataIsNan = hasNodata && std::isnan(nodata);
    for (float& v : out.values.values()) {
        if (std::isnan(v) || (hasNodata && !nodataIsNan && v == nodataF)) {
            v = std::numeric_limits<float>::quiet_NaN();
            ++out.nodataCount;
        } else if (!std::isfinite(v)) {
            v = std::numeric_limits<float>::quiet_NaN();  // +-inf heights are treated as nodata
            ++out.nodataCount;
        }
    }
    return out;
}

std::vector<Grid<float>> readRasterBands(const std::string& path, RasterSummary* summary) {
    if (summary) *summary = inspectRaster(path);
    DatasetPtr ds = openRaster(path);
    const auto width = static_cast<std::size_t>(ds->GetRasterXSize());
    const auto height = static_cast<std::size_t>(ds->GetRasterYSize());
    std::vector<Grid<float>> out;
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
        GDALRasterBand* band = ds->GetRasterBand(b);
        Grid<float> g(width, height);
        if (band->RasterIO(GF_Read, 0, 0, static_cast<int>(width), static_cast<int>(height), g.data(),
                           static_cast<int>(width), static_cast<int>(height), GDT_Float32, 0, 0) != CE_None)
            throw Error(withGdalReason("cannot read band " + std::to_string(b) + " of '" + path + "'"));
        int hasNodata = 0;
        const auto nodata = static_cast<float>(band->GetNoDataValue(&hasNodata));
        if (hasNodata)
            for (float& v : g.values())
                if (v == nodata) v = std::numeric_limits<float>::quiet_NaN();
        out.push_back(std::move(g));
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

void writeRaster(const std::string& path, const std::vector<OutputBand>& bands,
                 const GeoReference& ref, const WriteOptions& options,
                 const std::string& inputPath) {
    detail::ensureGdal();
    if (bands.empty()) throw Error("nothing to write to '" + path + "'");
    if (options.format != "GTiff" && options.format != "COG")
        throw Error("output format '" + options.format + "' is not supported (-of GTiff or COG)");

    std::error_code ec;
    if (!inputPath.empty() && fs::exists(path, ec) &&
        fs::equivalent(fs::path(path), fs::path(inputPath), ec))
        throw Error("output '" + path + "' would overwrite the input DEM; choose another -o");
    const fs::path parent = fs::absolute(fs::path(path)).parent_path();
    if (!fs::is_directory(parent, ec))
        throw Error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
    if (fs::is_directory(path, ec)) throw Error("cannot write '" + path + "': it is a directory");

    // Every band is stored in one data type (TIFF needs that): Byte only if all are masks.
    const bool allMasks = std::all_of(bands.begin(), bands.end(),
                                      [](const OutputBand& b) { return b.values == nullptr; });
    const GDALDataType type = allMasks ? GDT_Byte : GDT_Float32;
    const auto shapeOf = [](const OutputBand& b) {
        return b.values ? std::pair(b.values->width(), b.values->height())
                        : std::pair(b.mask->width(), b.mask->height());
    };
    const auto [width, height] = shapeOf(bands.front());
    for (const auto& b : bands) {
        if (!b.values && !b.mask) throw Error("internal: output band '" + b.description + "' is empty");
        if (shapeOf(b) != std::pair(width, height))
            throw Error("internal: output bands of '" + path + "' differ in size");
    }

    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(options.format.c_str());
    if (!driver) throw Error("GDAL has no '" + options.format + "' driver");
    validateUserCreationOptions(driver, options);
    const std::vector<std::string> co = creationOptions(options, type == GDT_Float32);
    CPLStringList coList;
    for (const auto& kv : co) coList.AddString(kv.c_str());

    // Write under a temporary name in the same folder and rename on success, so a failed or
    // interrupted run never leaves a partial file at `path`.
    fs::path tmpName = fs::path(path).filename();
    tmpName += ".tmp" + std::to_string(::getpid());
    const std::string tmp = (parent / tmpName).string();
    detail::takeGdalError();

    // GTiff is created directly and filled from the grids; COG can only be made by CreateCopy,
    // so it is staged in a MEM dataset first.
    const bool direct = options.format == "GTiff";
    DatasetPtr ds;
    if (direct) {
        ds.reset(driver->Create(tmp.c_str(), static_cast<int>(width), static_cast<int>(height),
                                static_cast<int>(bands.size()), type, coList.List()));
        if (!ds) {
            fs::remove(tmp, ec);
            throw Error(withGdalReason("cannot write '" + path + "'"));
        }
    } else {
        GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
        ds.reset(mem->Create("", static_cast<int>(width), static_cast<int>(height),
                             static_cast<int>(bands.size()), type, nullptr));
    }
    std::array<double, 6> gt = ref.geoTransform;
    ds->SetGeoTransform(gt.data());
    OGRSpatialReference srs;
    if (!ref.crsWkt.empty() && srs.importFromWkt(ref.crsWkt.c_str()) == OGRERR_NONE)
        ds->SetSpatialRef(&srs);
    for (const auto& [key, value] : options.metadata) ds->SetMetadataItem(key.c_str(), value.c_str());

    const bool replaceNan = !std::isnan(options.nodata);
    const auto nodataF = static_cast<float>(options.nodata);
    std::vector<float> buffer;
    for (std::size_t i = 0; i < bands.size(); ++i) {
        const OutputBand& b = bands[i];
        GDALRasterBand* out = ds->GetRasterBand(static_cast<int>(i) + 1);
        out->SetDescription(b.description.c_str());
        if (!b.unit.empty()) out->SetUnitType(b.unit.c_str());
        CPLErr err;
        if (type == GDT_Byte) {
            if (options.nodata >= 0 && options.nodata <= 255) out->SetNoDataValue(options.nodata);
            err = out->RasterIO(GF_Write, 0, 0, static_cast<int>(width), static_cast<int>(height),
                                const_cast<std::uint8_t*>(b.mask->data()), static_cast<int>(width),
                                static_cast<int>(height), GDT_Byte, 0, 0);
        } else {
            out->SetNoDataValue(options.nodata);
            // In strips of whole tile rows: a band that needs converting (a mask, or NaN to the
            // nodata value) goes through a strip-sized buffer that stays in cache, not a copy of
            // the whole band.
            err = CE_None;
            for (std::size_t r0 = 0; r0 < height && err == CE_None; r0 += kWriteStripRows) {
                const std::size_t rows = std::min(kWriteStripRows, height - r0);
                const float* data = nullptr;
                if (b.values && !replaceNan) {
                    data = b.values->rowPtr(r0);  // written as is: no copy
                } else {
                    buffer.resize(rows * width);
                    if (b.values) {
                        std::copy_n(b.values->rowPtr(r0), rows * width, buffer.begin());
                    } else {
                        std::copy_n(b.mask->rowPtr(r0), rows * width, buffer.begin());
                    }
                    if (replaceNan)
                        for (float& v : buffer)
                            if (std::isnan(v)) v = nodataF;
                    data = buffer.data();
                }
                err = out->RasterIO(GF_Write, 0, static_cast<int>(r0), static_cast<int>(width), static_cast<int>(rows),
                                    const_cast<float*>(data), static_cast<int>(width), static_cast<int>(rows),
                                    GDT_Float32, 0, 0);
            }
        }
        if (err != CE_None) {
            ds.reset();
            if (direct) fs::remove(tmp, ec);
            throw Error(withGdalReason(direct ? "cannot write band " + std::to_string(i + 1) + " of '" + path + "'"
                                              : "cannot fill band " + std::to_string(i + 1)));
        }
    }

    GDALDataset* written = direct ? ds.release()
                                  : driver->CreateCopy(tmp.c_str(), ds.get(), FALSE, coList.List(), nullptr, nullptr);
    if (!written) {
        fs::remove(tmp, ec);
        throw Error(withGdalReason("cannot write '" + path + "'"));
    }
    GDALClose(GDALDataset::ToHandle(written));
    const std::string closeError = detail::takeGdalError();
    if (!closeError.empty()) {
        fs::remove(tmp, ec);
        throw Error("cannot write '" + path + "' (" + closeError + ")");
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error("cannot write '" + path + "': rename failed (" + ec.message() + ")");
    }
}

struct RasterSink::State {
    std::string path, tmp, staged;  // final name; the file written; the streamed GeoTIFF of a COG
    std::size_t width, height;
    GeoReference ref;
    WriteOptions options;
    DatasetPtr ds;
    std::size_t bands = 0;
    bool committed = false;
};

RasterSink::RasterSink(std::string path, std::size_t width, std::size_t height, GeoReference ref,
                       WriteOptions options, const std::string& inputPath)
    : state_(std::make_unique<State>()) {
    detail::ensureGdal();
    if (options.format != "GTiff" && options.format != "COG")
        throw Error("output format '" + options.format + "' is not supported (-of GTiff or COG)");
    std::error_code ec;
    if (!inputPath.empty() && fs::exists(path, ec) && fs::equivalent(fs::path(path), fs::path(inputPath), ec))
        throw Error("output '" + path + "' would overwrite the input DEM; choose another -o");
    const fs::path parent = fs::absolute(fs::path(path)).parent_path();
    if (!fs::is_directory(parent, ec))
        throw Error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
    if (fs::is_directory(path, ec)) throw Error("cannot write '" + path + "': it is a directory");
    State& st = *state_;
    const std::string base = (parent / fs::path(path).filename()).string() + ".tmp" + std::to_string(::getpid());
    st.tmp = base;
    st.staged = options.format == "COG" ? base + ".stream.tif" : base;
    st.path = std::move(path);
    st.width = width;
    st.height = height;
    st.ref = std::move(ref);
    st.options = std::move(options);
}

RasterSink::~RasterSink() {
    if (!state_ || state_->committed) return;
    state_->ds.reset();
    std::error_code ec;
    fs::remove(state_->staged, ec);
    fs::remove(state_->tmp, ec);
}

void RasterSink::write(const CellWindow& w, const std::vector<OutputBand>& bands) {
    State& st = *state_;
    if (bands.empty()) throw Error("internal: nothing to write to '" + st.path + "'");
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    if (w.col1 > st.width || w.row1 > st.height || cols == 0 || rows == 0)
        throw Error("internal: window outside the output '" + st.path + "'");
    const bool allMasks = std::all_of(bands.begin(), bands.end(), [](const OutputBand& b) { return !b.values; });
    const GDALDataType type = allMasks ? GDT_Byte : GDT_Float32;
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
        for (const auto& kv : creationOptions(streamed, type == GDT_Float32)) co.AddString(kv.c_str());
        if (st.options.format == "COG") co.SetNameValue("COMPRESS", "ZSTD");
        detail::takeGdalError();
        st.ds.reset(gtiff->Create(st.staged.c_str(), static_cast<int>(st.width), static_cast<int>(st.height),
                                  static_cast<int>(bands.size()), type, co.List()));
        if (!st.ds) throw Error(withGdalReason("cannot write '" + st.path + "'"));
        std::array<double, 6> gt = st.ref.geoTransform;
        st.ds->SetGeoTransform(gt.data());
        OGRSpatialReference srs;
        if (!st.ref.crsWkt.empty() && srs.importFromWkt(st.ref.crsWkt.c_str()) == OGRERR_NONE)
            st.ds->SetSpatialRef(&srs);
        for (const auto& [key, value] : st.options.metadata) st.ds->SetMetadataItem(key.c_str(), value.c_str());
        for (std::size_t i = 0; i < bands.size(); ++i) {
            GDALRasterBand* out = st.ds->GetRasterBand(static_cast<int>(i) + 1);
            out->SetDescription(bands[i].description.c_str());
            if (!bands[i].unit.empty()) out->SetUnitType(bands[i].unit.c_str());
            if (type == GDT_Float32 || (st.options.nodata >= 0 && st.options.nodata <= 255))
                out->SetNoDataValue(st.options.nodata);
        }
        st.bands = bands.size();
    }
    if (bands.size() != st.bands) throw Error("internal: windows of '" + st.path + "' differ in bands");
    const bool replaceNan = !std::isnan(st.options.nodata);
    const auto nodataF = static_cast<float>(st.options.nodata);
    std::vector<float> buffer;
    for (std::size_t i = 0; i < bands.size(); ++i) {
        const OutputBand& b = bands[i];
        GDALRasterBand* out = st.ds->GetRasterBand(static_cast<int>(i) + 1);
        CPLErr err;
        if (type == GDT_Byte) {
            err = out->RasterIO(GF_Write, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                static_cast<int>(rows), const_cast<std::uint8_t*>(b.mask->data()),
                                static_cast<int>(cols), static_cast<int>(rows), GDT_Byte, 0, 0);
        } else {
            buffer.resize(cols * rows);
            if (b.values) {
                std::copy_n(b.values->data(), cols * rows, buffer.begin());
            } else {
                std::copy_n(b.mask->data(), cols * rows, buffer.begin());
            }
            if (replaceNan)
                for (float& v : buffer)
                    if (std::isnan(v)) v = nodataF;
            err = out->RasterIO(GF_Write, static_cast<int>(w.col0), static_cast<int>(w.row0), static_cast<int>(cols),
                                static_cast<int>(rows), buffer.data(), static_cast<int>(cols), static_cast<int>(rows),
                                GDT_Float32, 0, 0);
        }
        if (err != CE_None) throw Error(withGdalReason("cannot write band " + std::to_string(i + 1) + " of '" + st.path + "'"));
    }
}

void RasterSink::commit() {
    State& st = *state_;
    if (!st.ds) throw Error("internal: nothing was written to '" + st.path + "'");
    std::error_code ec;
    if (st.options.format == "COG") {
        GDALDriver* cog = GetGDALDriverManager()->GetDriverByName("COG");
        if (!cog) throw Error("GDAL has no 'COG' driver");
        validateUserCreationOptions(cog, st.options);
        CPLStringList co;
        const bool isFloat = st.ds->GetRasterBand(1)->GetRasterDataType() == GDT_Float32;
        for (const auto& kv : creationOptions(st.options, isFloat)) co.AddString(kv.c_str());
        detail::takeGdalError();
        GDALDataset* copy = cog->CreateCopy(st.tmp.c_str(), st.ds.get(), FALSE, co.List(), nullptr, nullptr);
        if (!copy) throw Error(withGdalReason("cannot write '" + st.path + "'"));
        GDALClose(GDALDataset::ToHandle(copy));
    }
    detail::takeGdalError();
    st.ds.reset();  // flushes the streamed file
    const std::string closeError = detail::takeGdalError();
    if (!closeError.empty()) throw Error("cannot write '" + st.path + "' (" + closeError + ")");
    if (st.staged != st.tmp) fs::remove(st.staged, ec);
    fs::rename(st.tmp, st.path, ec);
    if (ec) throw Error("cannot write '" + st.path + "': rename failed (" + ec.message() + ")");
    st.committed = true;
}

}  // namespace demlight
