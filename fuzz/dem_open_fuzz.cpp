// libFuzzer target: opening a DEM (openDem in demlight/geo/dem.h) from bytes that GDAL reads as a VRT or
// a GeoTIFF, then reading a corner window of it: headers that lie about their size, sources that
// point anywhere, broken tags. Run under a memory cap (scripts/fuzz.sh passes -rss_limit_mb):
// no input may make the opening hold memory in proportion to the size a header declares, crash,
// or fail other than by demlight::Error. The first byte picks the name's extension (so the
// driver); the rest is the file.
#include "demlight/geo/dem.h"
#include "demlight/geo/gdal_session.h"
#include "demlight/geo/raster.h"
#include "demlight/core/error.h"

#include <cpl_conv.h>
#include <cpl_vsi.h>

#include <algorithm>
#include <cstdint>
#include <string>

namespace {

/// Opened DEMs wider or taller than this are not read further: opening costs a PROJ call per
/// row, which at 2^22 rows outlasts the fuzzer's per-input timeout under the sanitizers.
constexpr std::size_t kOpenedSideCells = 1 << 16;
/// The corner window read from an opened DEM (cells a side).
constexpr std::size_t kWindowCells = 64;

void configureGdal() {
    demlight::detail::ensureGdal();
    // No network and no raw device reads from a VRT's sources: the fuzzer explores the
    // parsers, not this machine's files or a remote server's latency.
    CPLSetConfigOption("GDAL_VRT_ENABLE_RAWRASTERBAND", "NO");
    CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "1");
    CPLSetConfigOption("GDAL_HTTP_MAX_RETRY", "0");
    CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS", ".none");
    CPLSetConfigOption("GDAL_DISABLE_READDIR_ON_OPEN", "EMPTY_DIR");
    CPLSetConfigOption("CPL_DEBUG", "OFF");
    CPLSetErrorHandler(CPLQuietErrorHandler);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool configured = (configureGdal(), true);
    (void)configured;
    if (size < 1) return 0;
    const std::string path = std::string("/vsimem/dem_open_fuzz") + ((data[0] & 1) ? ".vrt" : ".tif");
    VSILFILE* f = VSIFileFromMemBuffer(path.c_str(), const_cast<GByte*>(data + 1), size - 1, FALSE);
    if (!f) return 0;
    VSIFCloseL(f);
    try {
        const demlight::RasterBand header = demlight::readRasterHeader(path);
        if (header.width <= kOpenedSideCells && header.height <= kOpenedSideCells) {
            const demlight::Dem dem = demlight::openDem(path);
            const demlight::CellWindow corner{0, 0, std::min(kWindowCells, dem.band.width),
                                              std::min(kWindowCells, dem.band.height)};
            (void)demlight::readRasterWindow(path, corner);
        } else {
            // Past the opened size: the opening must refuse or cost no more than at it.
            (void)demlight::openDem(path, {}, [](double, const std::string&) { return false; });
        }
    } catch (const demlight::Error&) {
    }
    VSIUnlink(path.c_str());
    return 0;
}
