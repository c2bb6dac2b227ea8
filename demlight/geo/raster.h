// Raster I/O through GDAL. This folder is the only code that includes GDAL headers.
#pragma once

#include "demlight/core/grid.h"
#include "demlight/core/progress.h"

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// Where a raster sits on the earth: GDAL geotransform (north-up only) and CRS as WKT.
struct GeoReference {
    /// GDAL order: originX, pixelWidth, rotX (0), originY, rotY (0), pixelHeight (< 0 north-up).
    std::array<double, 6> geoTransform{0, 1, 0, 0, 0, -1};
    std::string crsWkt;
};

/// Band 1 of a raster, as float, with NaN wherever the source held its nodata value (or NaN).
/// The values are the band's own (raw) values: GDAL's scale, offset and unit are recorded beside
/// them, not applied, so that nodata stays comparable and loadDem is the one place heights are
/// converted to metres.
struct RasterBand {
    Grid<float> values;
    /// The raster's size in cells (values may hold a window of it, or nothing: readRasterHeader).
    std::size_t width = 0, height = 0;
    /// The source's nodata value, if it declared one (raw, as declared; kept so outputs can carry
    /// it over).
    std::optional<double> nodata;
    /// GDAL band scale and offset: a raw value v stands for v * scale + offset (in `unit`).
    double scale = 1.0;
    double offset = 0.0;
    /// GDAL band unit type as declared ("m", "ft", ...); empty when the band declares none.
    std::string unit;
    GeoReference ref;
    std::string path;
    std::size_t nodataCount = 0;
};

/// Reads band 1 of any raster GDAL opens, including GDAL virtual paths (/vsizip/, /vsigzip/,
/// /vsicurl/, ...). Throws Error for missing or unreadable files, rasters without a CRS, and
/// rotated or sheared geotransforms.
RasterBand readRasterBand(const std::string& path);

/// Band 1's georeference, nodata, scale, offset, unit and size, without its values (empty);
/// the checks of readRasterBand.
RasterBand readRasterHeader(const std::string& path);

/// Band 1's values in `window` (cells of the raster, inside it) as readRasterBand converts them
/// (NaN for nodata and +-inf). Counts the window's nodata cells into *nodataCount when given.
Grid<float> readRasterWindow(const std::string& path, const CellWindow& window, std::size_t* nodataCount = nullptr);

/// The files GDAL reads for the raster at `path` (GDALDataset::GetFileList: the file itself, its
/// sidecars, and a VRT's sources); empty for a dataset that names none (a virtual path GDAL
/// keeps in memory).
std::vector<std::string> rasterFiles(const std::string& path);

struct RasterSummary;

/// A one-band Float32 GeoTIFF in GDAL's memory file system (/vsimem/): `values` on `ref`, with
/// `nodata` declared when given. ref.crsWkt may be WKT or any definition GDAL reads
/// (OGRSpatialReference::SetFromUserInput: "EPSG:32610", PROJ strings); an empty or unreadable one
/// leaves the raster without a CRS, which readers then refuse. The file is removed with the object.
/// It lets values held in memory pass through the readers of files (demFromArray).
class MemoryRaster {
public:
    MemoryRaster(const Grid<float>& values, const GeoReference& ref, std::optional<double> nodata);
    MemoryRaster(const MemoryRaster&) = delete;
    MemoryRaster& operator=(const MemoryRaster&) = delete;
    ~MemoryRaster();
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

/// Reads every band of a raster as float (nodata and NaN become NaN), without resampling.
std::vector<Grid<float>> readRasterBands(const std::string& path, RasterSummary* summary = nullptr);

/// One band of any raster GDAL opens, for a picture of it (demlight quicklook).
struct PictureBand {
    /// The band's values as float, GDAL scale and offset applied; NaN at nodata and NaN cells.
    Grid<float> values;
    int index = 1;  ///< 1-based band number
    std::size_t bandCount = 0;
    std::string description, unit;  ///< GDAL's band description and unit type (may be empty)
    std::map<std::string, std::string> metadata;  ///< the dataset's, default domain
    std::array<double, 6> geoTransform{0, 1, 0, 0, 0, 1};  ///< GDAL's (identity without one)
    bool geographic = false;  ///< the CRS is latitude/longitude
};

/// Reads band `band` of `path`: a 1-based number or a band description. Throws Error naming the
/// raster's bands when there is no such band.
PictureBand readPictureBand(const std::string& path, const std::string& band);

/// Reads every band of overview `level` (0 = the largest) of a raster as float (nodata and NaN
/// become NaN), for checks of written files. Throws Error when there is no such overview.
std::vector<Grid<float>> readRasterOverview(const std::string& path, int level);

/// Reads all bands of a raster as float, resampled (bilinear) onto `target`'s grid of
/// `width` x `height`. Used for albedo and colour rasters.
std::vector<Grid<float>> readRasterResampled(const std::string& path, const GeoReference& target,
                                             std::size_t width, std::size_t height);

/// How a band's overviews (COG) are computed from its cells, by what the band holds.
enum class Resampling {
    Average,  ///< mean of the cells (nodata left out): fractions, irradiance, angles, lengths
    Nearest,  ///< one of the cells: flags, masks, and bands with marker values (-1 "never lit",
              ///< -90 "no terrain") that a mean would blend into values that mean nothing
};

/// One output band: values with NaN for nodata, a description and a unit.
struct OutputBand {
    const Grid<float>* values = nullptr;   // Float32 bands
    const Grid<std::uint8_t>* mask = nullptr;  // or Byte bands (used when values is null)
    std::string description;
    std::string unit;
    Resampling resampling = Resampling::Average;
};

/// 16-bit fixed-point storage of Float32 bands (the compact horizon maps of Hoffman & Mitchell
/// 2001a): a value v is stored in Int16 as round((v - offset) / scale), clamped to
/// +-kFixedPoint16Max, with the band's GDAL scale and offset set, so that every reader that applies
/// them (gdalinfo -stats, QGIS, rasterio's masked and scaled reads) gets v back within scale / 2.
/// NaN (nodata) is stored as `nodata`, outside the clamped range.
struct FixedPoint16 {
    double scale = 1.0;
    double offset = 0.0;
    std::int16_t nodata = std::numeric_limits<std::int16_t>::min();
};
/// The largest stored magnitude: -32768 stays free for nodata.
inline constexpr std::int16_t kFixedPoint16Max = std::numeric_limits<std::int16_t>::max();

struct WriteOptions {
    /// GDAL driver: "GTiff" (default) or "COG".
    std::string format = "GTiff";
    /// Extra GDAL creation options, KEY=VALUE; they override the defaults
    /// (GTiff: TILED=YES, COMPRESS=ZSTD, ZSTD_LEVEL=1, PREDICTOR=3 for Float32, 2 for Int16 or 1
    /// for Byte, INTERLEAVE=BAND, NUM_THREADS=ALL_CPUS, BIGTIFF=IF_SAFER; COG: COMPRESS=DEFLATE,
    /// PREDICTOR=YES/NO, ...).
    std::vector<std::string> creationOptions;
    /// Dataset metadata items (DEMLIGHT_* keys: command line, version, parameters).
    std::map<std::string, std::string> metadata;
    /// Nodata value written for NaN cells of Float32 bands (NaN by default); Byte bands declare
    /// it as their nodata value when it is in 0..255 (their cells are written as given).
    double nodata = std::numeric_limits<double>::quiet_NaN();
    /// Store the Float32 bands as 16-bit fixed point (Int16 with scale and offset) instead; Byte
    /// (mask) rasters are unaffected, and `nodata` is then FixedPoint16::nodata.
    std::optional<FixedPoint16> fixedPoint;
    /// Called while writing (stage "write"); returning false stops: the temporary file is removed
    /// and Cancelled thrown. Empty: never stopped.
    ProgressFn progress;
};

/// Throws Error unless `path` names a GeoTIFF: its extension, if it has one, must be .tif or .tiff
/// (any case). GTiff and COG both write GeoTIFF; a raster named .png or .jpg would be a TIFF that
/// every reader mistakes for a picture.
void checkRasterPath(const std::string& path);

/// Caps GDAL's block cache at `bytes`. The cache holds the blocks of rasters being read and
/// written until they go to disk; GDAL's default is 5 % of the machine's memory, which a tiled
/// run streaming gigabytes of output fills whatever its memory budget.
void setRasterCacheBytes(double bytes);

/// Largest block side (cells) a creation option may set (BLOCKXSIZE, BLOCKYSIZE; COG's
/// BLOCKSIZE): the writer and GDAL's block cache hold blocks whole, once per compressing thread,
/// and 4096 x 4096 Float32 cells are 64 MiB.
inline constexpr long long kMaxBlockSideCells = 4096;

/// Why one user creation option (KEY=VALUE) asks for blocks the writer cannot hold: a block
/// side (BLOCKXSIZE, BLOCKYSIZE, BLOCKSIZE) that is not a whole number from 1 to
/// kMaxBlockSideCells. Empty for any other option, and for a block side in range.
std::string blockSizeProblem(const std::string& option);

/// Checks user creation options (KEY=VALUE) against `format`'s driver ("GTiff" or "COG") as
/// writeRaster will: a key or value the driver does not list, or a block size beyond
/// blockSizeProblem's range, is an Error. For checking them before a long computation.
void checkCreationOptions(const std::string& format, const std::vector<std::string>& userOptions);

/// Writes bands to `path` atomically: a temporary name in the same folder, renamed on success
/// (demlight/geo/output_file.h); a failure or a cancel leaves neither `path` changed nor a temporary file.
/// All bands must be the same shape. Refuses to overwrite `inputPath` when given, a `path` that is not
/// a regular file (checkOutputFile) or not named as a GeoTIFF (checkRasterPath). COG overviews are
/// built per band with its Resampling, unless the creation options choose the overviews (RESAMPLING,
/// OVERVIEW_RESAMPLING, OVERVIEWS, or a reprojection: TILING_SCHEME, TARGET_SRS); GDAL's COG driver
/// would resample every band alike (cubic by default, which overshoots: a visibility of -0.24 or 1.19).
void writeRaster(const std::string& path, const std::vector<OutputBand>& bands,
                 const GeoReference& ref, const WriteOptions& options,
                 const std::string& inputPath = {});

/// Writes to `path` a copy of the GeoTIFF `source` (a file writeRaster wrote) with the dataset
/// metadata items `metadata` set, each replacing the item of that key: the cells, bands,
/// georeference and layout are the source's, not encoded again. For a raster whose cells equal
/// a file already written (a time-lapse's night frames). Atomic and checked as writeRaster:
/// a temporary name in `path`'s folder, renamed on success; GDAL rewrites the metadata in the
/// copy's TIFF directory (appended to the file, the tiles untouched).
void copyRasterWithMetadata(const std::string& source, const std::string& path,
                            const std::map<std::string, std::string>& metadata);

/// What a written raster holds, for checks and reports (read back through GDAL).
struct RasterSummary {
    std::string driver;
    std::size_t width = 0, height = 0;
    GeoReference ref;
    std::vector<std::string> descriptions;  // per band
    std::vector<std::string> units;         // per band
    std::vector<std::string> dataTypes;     // per band, GDAL names ("Float32")
    std::optional<double> nodata;           // band 1
    std::size_t overviews = 0;              // band 1's overview levels
    std::map<std::string, std::string> metadata;  // default domain
    std::map<std::string, std::string> imageStructure;  // COMPRESSION, LAYOUT, ...
};
RasterSummary inspectRaster(const std::string& path);

/// A raster written window by window as the tiles of a product complete, so that no more than
/// one tile of each band is held in memory. The file is created under a temporary name in the
/// folder of `path` at the first window (band names, units and types come from it), every band
/// of each window is written as it arrives, and commit() renames the file to `path` (a COG is
/// streamed to a tiled GeoTIFF first and copied to COG layout at commit). Destroyed without
/// commit (an error, Ctrl-C), it removes its temporaries: nothing is left under `path`.
class RasterSink {
public:
    /// A `width` x `height` raster on `ref`. Checks the path as writeRaster does.
    RasterSink(std::string path, std::size_t width, std::size_t height, GeoReference ref, WriteOptions options,
               const std::string& inputPath = {});
    RasterSink(const RasterSink&) = delete;
    RasterSink& operator=(const RasterSink&) = delete;
    ~RasterSink();
    /// Writes `bands` (all the window's size, the same bands in the same order every time) at
    /// the window's cells.
    void write(const CellWindow& window, const std::vector<OutputBand>& bands);
    /// Sets a dataset metadata item known only once every window is written (a mean over the
    /// raster); after the first write, before commit.
    void setMetadata(const std::string& key, const std::string& value);
    /// Closes, converts (COG) and renames the file to its path. Throws Error when GDAL fails.
    void commit();

private:
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace demlight
