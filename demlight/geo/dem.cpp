#include "demlight/geo/dem.h"

#include "demlight/geo/gdal_session.h"
#include "demlight/core/error.h"

#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string_view>

namespace demlight {
namespace {

/// Metres per international foot (exact by definition).
constexpr double kFootM = 0.3048;
/// Metres per US survey foot (exact by definition).
constexpr double kUsSurveyFootM = 1200.0 / 3937.0;

struct VerticalUnit {
    std::string_view name;  // lower case
    double metres;
};
constexpr VerticalUnit kVerticalUnits[] = {
    {"", 1.0},       {"m", 1.0},      {"metre", 1.0},          {"meter", 1.0},
    {"metres", 1.0}, {"meters", 1.0}, {"ft", kFootM},          {"foot", kFootM},
    {"feet", kFootM}, {"international foot", kFootM},          {"us survey foot", kUsSurveyFootM},
    {"us-ft", kUsSurveyFootM},        {"ftus", kUsSurveyFootM}, {"us survey feet", kUsSurveyFootM},
    {"cm", 0.01},    {"dm", 0.1},     {"mm", 0.001},           {"km", 1000.0},
};
/// The short list messages offer (every spelling above is accepted).
constexpr const char* kKnownUnitsText = "m, ft, US survey foot, cm, dm, mm, km";

/// A number for a message, to 10 significant digits.
std::string formatValue(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.10g", v);
    return text;
}

std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

void checkHeightOptions(const HeightOptions& o) {
    if (o.zFactor != 0 && !(std::isfinite(o.zFactor) && o.zFactor > 0))
        throw ParameterError("{z_factor} " + formatValue(o.zFactor) +
                    " must be a finite number > 0 (metres per height unit; 0 = not set)");
    if (o.zFactor != 0 && !o.zUnit.empty())
        throw ParameterError("{z_unit} \"" + o.zUnit + "\" and {z_factor} " +
                    formatValue(o.zFactor) + " exclude each other: set one");
    if (!o.zUnit.empty() && (trimmed(o.zUnit).empty() || !metresPerUnit(o.zUnit)))
        throw ParameterError("{z_unit} \"" + o.zUnit + "\" is not a vertical unit demlight knows (" +
                    kKnownUnitsText + ")");
}

/// The band's scale and offset, and metres per unit from the options or else the band's unit.
HeightTransform heightTransform(const RasterBand& band, const HeightOptions& o) {
    if (!std::isfinite(band.scale) || band.scale == 0 || !std::isfinite(band.offset))
        throw Error("'" + band.path + "' declares band scale " + formatValue(band.scale) + " and offset " +
                    formatValue(band.offset) + ": heights need a finite, non-zero scale and a finite offset");
    HeightTransform tr;
    tr.scale = band.scale;
    tr.offset = band.offset;
    tr.unit = band.unit;
    if (o.zFactor != 0) {
        tr.toMetres = o.zFactor;
        tr.source = "zFactor option";
    } else if (!o.zUnit.empty()) {
        tr.unit = o.zUnit;
        tr.toMetres = *metresPerUnit(o.zUnit);
        tr.source = "zUnit option";
    } else if (trimmed(band.unit).empty()) {
        tr.source = "default (no unit declared: metres)";
    } else if (const auto metres = metresPerUnit(band.unit)) {
        tr.toMetres = *metres;
        tr.source = "band";
    } else {
        throw ParameterError("'" + band.path + "' declares its heights in unit \"" + band.unit +
                             "\", which demlight cannot convert to metres; set {z_unit} to the unit it means (" +
                             kKnownUnitsText + ") or {z_factor} to metres per unit");
    }
    return tr;
}

}  // namespace

Grid<float> heightsInMetres(const RasterBand& band, const HeightTransform& tr) { return heightsInMetres(band.values, band.path, tr); }

Grid<float> heightsInMetres(Grid<float> heights, const std::string& path, const HeightTransform& tr) {
    // The identity does no arithmetic at all, so metre DEMs keep their values bit for bit.
    if (tr.scale == 1 && tr.offset == 0 && tr.toMetres == 1) return heights;
    for (float& v : heights.values()) {
        if (std::isnan(v)) continue;
        const double metres = (static_cast<double>(v) * tr.scale + tr.offset) * tr.toMetres;
        if (!(std::abs(metres) <= std::numeric_limits<float>::max()))
            throw Error("'" + path + "': value " + formatValue(v) + " becomes " + formatValue(metres) +
                        " m after scale " + formatValue(tr.scale) + ", offset " + formatValue(tr.offset) +
                        " and x " + formatValue(tr.toMetres) + ", beyond what a height can hold");
        v = static_cast<float>(metres);
    }
    return heights;
}

namespace {

/// Convergence lattice spacing (cells). Gamma varies smoothly (about dLambda * sin(phi)), so
/// bilinear interpolation between nodes 64 cells apart is accurate to far below 0.001 deg.
constexpr std::size_t kConvergenceStepCells = 64;
/// Most nodes of the convergence lattice (4 MiB of floats, two PROJ calls each): a DEM whose
/// lattice every 64 cells would be larger (past 65 000 cells a side) gets a coarser one, so that
/// opening it costs the same whatever size its header declares.
constexpr std::size_t kMaxConvergenceNodes = std::size_t{1} << 20;
/// Points per PROJ call when transforming rows of points (rows per batch of geodesics), and
/// between two calls of the progress callback.
constexpr std::size_t kTransformBatch = 4096;
/// Transforms an opening makes before it reports progress ("opening DEM"): below this it takes
/// a fraction of a second.
constexpr std::size_t kReportedTransforms = std::size_t{1} << 18;
/// Most cells a DEM may have a side: its geometry holds a few numbers per row (cell sizes,
/// latitude; 40 bytes with the frame's copies) and a pass over its heights at least a row at
/// once, so a header declaring billions of either would ask for gigabytes before any height is
/// read. 2^22 cells is 4 000 km at 1 m cells.
constexpr std::size_t kMaxSideCells = std::size_t{1} << 22;
/// Latitude offset used to find the true-north direction numerically (degrees).
constexpr double kNorthProbeDeg = 1e-4;

struct TransformDeleter {
    void operator()(OGRCoordinateTransformation* t) const {
        OGRCoordinateTransformation::DestroyCT(t);
    }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

struct CrsPair {
    OGRSpatialReference grid;
    OGRSpatialReference geographic;  // the grid CRS's own geographic CRS, lon/lat order
    TransformPtr toGeo;
    TransformPtr fromGeo;
};

std::unique_ptr<CrsPair> makeTransforms(const std::string& wkt) {
    auto p = std::make_unique<CrsPair>();
    p->grid.importFromWkt(wkt.c_str());
    p->grid.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    p->geographic.CopyGeogCSFrom(&p->grid);
    p->geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    p->toGeo.reset(OGRCreateCoordinateTransformation(&p->grid, &p->geographic));
    p->fromGeo.reset(OGRCreateCoordinateTransformation(&p->geographic, &p->grid));
    if (!p->toGeo || !p->fromGeo)
        throw Error("cannot relate the DEM's CRS to latitude/longitude (" +
                    detail::takeGdalError() + ")");
    return p;
}

CrsInfo describeCrs(const std::string& wkt, const std::string& path) {
    OGRSpatialReference srs;
    if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE)
        throw Error("'" + path + "' has a CRS GDAL cannot interpret");
    CrsInfo info;
    info.name = srs.GetName() ? srs.GetName() : "unnamed";
    info.geographic = srs.IsGeographic();
    if (!info.geographic && !srs.IsProjected())
        throw Error("'" + path + "' has a CRS that is neither geographic nor projected (" +
                    info.name + ")");
    if (!info.geographic) info.linearUnitM = srs.GetLinearUnits(nullptr);
    OGRErr err = OGRERR_NONE;
    info.semiMajorM = srs.GetSemiMajor(&err);
    info.inverseFlattening = srs.GetInvFlattening(&err);
    const char* code = srs.GetAuthorityCode(nullptr);
    const char* authority = srs.GetAuthorityName(nullptr);
    if (code && authority && std::string(authority) == "EPSG") {
        info.epsg = std::atoi(code);
    } else {
        // No code in the file: ask PROJ for an equivalent definition it is sure of.
        OGRSpatialReference copy(srs);
        if (copy.AutoIdentifyEPSG() == OGRERR_NONE && copy.GetAuthorityCode(nullptr))
            info.epsg = std::atoi(copy.GetAuthorityCode(nullptr));
    }
    // Some drivers (USGS DEM) give a CRS without a name: take the identified code's.
    if (info.epsg && (!srs.GetName() || std::string(srs.GetName()).empty() || std::string(srs.GetName()) == "unnamed")) {
        OGRSpatialReference byCode;
        if (byCode.importFromEPSG(*info.epsg) == OGRERR_NONE && byCode.GetName()) info.name = byCode.GetName();
    }
    return info;
}

/// Per-row cell sizes of rows [row0, row1) of a geographic grid on the CRS's ellipsoid: the arc
/// of the parallel for the width, the geodesic along the meridian for the height.
void geographicCellSizes(const CrsInfo& crs, const GeoReference& ref, std::size_t row0, std::size_t row1,
                         Terrain& t) {
    const double f = crs.inverseFlattening > 0 ? 1.0 / crs.inverseFlattening : 0.0;
    const GeographicLib::Geodesic geodesic(crs.semiMajorM, f);
    const GeographicLib::Ellipsoid ellipsoid(crs.semiMajorM, f);
    const auto& gt = ref.geoTransform;
    const double dLonRad = gt[1] * M_PI / 180.0;
    for (std::size_t r = row0; r < row1; ++r) {
        const double latTop = gt[3] + static_cast<double>(r) * gt[5];
        const double latBottom = latTop + gt[5];
        const double lat = std::clamp(0.5 * (latTop + latBottom), -90.0, 90.0);
        double s12 = 0;
        geodesic.Inverse(std::clamp(latBottom, -90.0, 90.0), 0.0, std::clamp(latTop, -90.0, 90.0),
                         0.0, s12);
        t.cellHeightM[r] = std::abs(s12);
        t.cellWidthM[r] = ellipsoid.CircleRadius(lat) * dLonRad;
        t.rowLatitudeDeg[r] = lat;
    }
}

}  // namespace

class LatLonTransform {
public:
    explicit LatLonTransform(const std::string& wkt) : crs_(makeTransforms(wkt)) {}
    /// Grid CRS x/y to (lat, lon); false if PROJ cannot.
    bool apply(double x, double y, double& lat, double& lon) const {
        lon = x, lat = y;
        return crs_->toGeo->Transform(1, &lon, &lat);
    }

private:
    std::unique_ptr<CrsPair> crs_;
};

std::optional<double> metresPerUnit(const std::string& unit) {
    std::string key = trimmed(unit);
    std::transform(key.begin(), key.end(), key.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const auto& u : kVerticalUnits)
        if (u.name == key) return u.metres;
    return std::nullopt;
}

std::size_t convergenceStepCells(std::size_t width, std::size_t height) {
    std::size_t step = kConvergenceStepCells;
    const auto nodes = [&](std::size_t cells) { return (std::max<std::size_t>(cells, 1) - 1) / step + 2; };
    while (nodes(width) * nodes(height) > kMaxConvergenceNodes) step *= 2;
    return step;
}

Dem openDem(const std::string& path, const HeightOptions& heights, const ProgressFn& progress) {
    checkHeightOptions(heights);
    Dem dem;
    dem.band = readRasterHeader(path);
    const std::size_t width = dem.band.width;
    const std::size_t height = dem.band.height;
    if (width > kMaxSideCells || height > kMaxSideCells)
        throw Error("'" + path + "' declares " + std::to_string(width) + " x " + std::to_string(height) +
                    " cells; demlight opens DEMs of at most " + std::to_string(kMaxSideCells) +
                    " cells a side (cut it with gdal_translate -srcwin)");
    dem.crs = describeCrs(dem.band.ref.crsWkt, path);

    dem.heights = heightTransform(dem.band, heights);

    Terrain& t = dem.terrain;
    t.cellWidthM.resize(height);
    t.cellHeightM.resize(height);
    t.rowLatitudeDeg.resize(height);
    const auto& gt = dem.band.ref.geoTransform;

    if (dem.crs.geographic) {
        // Rows past a pole have no cells on the ellipsoid (a zero width, then every command's
        // "cell sizes must be positive"): say what is wrong with the georeference instead.
        const double north = std::max(gt[3], gt[3] + static_cast<double>(height) * gt[5]);
        const double south = std::min(gt[3], gt[3] + static_cast<double>(height) * gt[5]);
        constexpr double kRoundingDeg = 1e-9;  // an edge at 90 written as 90.0000000001
        if (north > 90 + kRoundingDeg || south < -90 - kRoundingDeg)
            throw Error("'" + path + "' reaches latitudes beyond the poles (" + formatValue(south) + " .. " +
                        formatValue(north) + " degrees): check its geotransform (rows must lie within -90 .. 90)");
        // A geodesic per row, in batches; a caller asked to stop hears of it between them.
        for (std::size_t r0 = 0; r0 < height; r0 += kTransformBatch) {
            geographicCellSizes(dem.crs, dem.band.ref, r0, std::min(height, r0 + kTransformBatch), t);
            if (progress && height >= kReportedTransforms &&
                !progress(static_cast<double>(std::min(height, r0 + kTransformBatch)) / static_cast<double>(height),
                          "opening DEM"))
                throw Cancelled();
        }
        return dem;
    }

    // Projected: cell size from the geotransform in the CRS's linear unit.
    std::fill(t.cellWidthM.begin(), t.cellWidthM.end(), gt[1] * dem.crs.linearUnitM);
    std::fill(t.cellHeightM.begin(), t.cellHeightM.end(), -gt[5] * dem.crs.linearUnitM);
    dem.toLatLon = std::make_shared<LatLonTransform>(dem.band.ref.crsWkt);
    auto crs = makeTransforms(dem.band.ref.crsWkt);

    // Meridian convergence on a coarse lattice: the direction of true north in grid
    // coordinates, found by stepping a little north in latitude and projecting back.
    const std::size_t step = convergenceStepCells(width, height);
    const std::size_t ni = (width - 1) / step + 2;
    const std::size_t nj = (height - 1) / step + 2;

    // The work is one PROJ call per row and two per lattice node, in batches; a caller asked
    // to stop hears of it between batches.
    const std::size_t work = height + 2 * ni * nj;
    std::size_t done = 0;
    const auto advance = [&](std::size_t points) {
        done += points;
        if (progress && work >= kReportedTransforms &&
            !progress(static_cast<double>(done) / static_cast<double>(work), "opening DEM"))
            throw Cancelled();
    };
    std::vector<double> xs, ys;
    std::vector<int> ok;
    // Transforms the first n points (xs, ys) in place through `ct`; false, with `failed` its
    // index, at a point PROJ cannot transform.
    const auto transform = [&](OGRCoordinateTransformation& ct, std::size_t n, std::size_t& failed) {
        ok.assign(n, 0);
        ct.Transform(static_cast<int>(n), xs.data(), ys.data(), nullptr, ok.data());
        for (failed = 0; failed < n; ++failed)
            if (!ok[failed]) return false;
        return true;
    };

    const double midCol = 0.5 * static_cast<double>(width);
    for (std::size_t r0 = 0; r0 < height; r0 += kTransformBatch) {
        const std::size_t n = std::min(kTransformBatch, height - r0);
        xs.assign(n, gt[0] + midCol * gt[1]);
        ys.resize(n);
        for (std::size_t k = 0; k < n; ++k) ys[k] = gt[3] + (static_cast<double>(r0 + k) + 0.5) * gt[5];
        std::size_t failed = 0;
        if (!transform(*crs->toGeo, n, failed))
            throw Error("cannot find latitude/longitude of cell (" + std::to_string(midCol) + ", " +
                        std::to_string(static_cast<double>(r0 + failed) + 0.5) + ") of '" + path + "'");
        std::copy_n(ys.begin(), n, t.rowLatitudeDeg.begin() + static_cast<std::ptrdiff_t>(r0));
        advance(n);
    }

    t.convergence.stepCells = step;
    t.convergence.gammaDeg = Grid<float>(ni, nj);
    std::vector<double> gridX, gridY;
    for (std::size_t j = 0; j < nj; ++j) {
        const double row = static_cast<double>(std::min(j * step, height - 1)) + 0.5;
        for (std::size_t i0 = 0; i0 < ni; i0 += kTransformBatch) {
            const std::size_t n = std::min(kTransformBatch, ni - i0);
            gridX.resize(n), gridY.resize(n), xs.resize(n), ys.resize(n);
            for (std::size_t k = 0; k < n; ++k) {
                const double col = static_cast<double>(std::min((i0 + k) * step, width - 1)) + 0.5;
                gridX[k] = xs[k] = gt[0] + col * gt[1];
                gridY[k] = ys[k] = gt[3] + row * gt[5];
            }
            const auto colOf = [&](std::size_t k) { return static_cast<double>(std::min((i0 + k) * step, width - 1)) + 0.5; };
            std::size_t failed = 0;
            if (!transform(*crs->toGeo, n, failed))
                throw Error("cannot find latitude/longitude of cell (" + std::to_string(colOf(failed)) + ", " +
                            std::to_string(row) + ") of '" + path + "'");
            for (std::size_t k = 0; k < n; ++k) ys[k] = std::min(ys[k] + kNorthProbeDeg, 90.0);
            if (!transform(*crs->fromGeo, n, failed))
                throw Error("cannot project a point near cell (" + std::to_string(colOf(failed)) + ", " +
                            std::to_string(row) + ") of '" + path + "'");
            for (std::size_t k = 0; k < n; ++k) {
                // True north points at angle alpha clockwise from grid north; grid north therefore
                // lies at -alpha clockwise from true north.
                const double alphaDeg = std::atan2(xs[k] - gridX[k], ys[k] - gridY[k]) * 180.0 / M_PI;
                t.convergence.gammaDeg(i0 + k, j) = static_cast<float>(-alphaDeg);
            }
            advance(2 * n);
        }
    }
    return dem;
}

Dem loadDem(const std::string& path, const HeightOptions& heights) {
    checkHeightOptions(heights);
    RasterBand band = readRasterBand(path);
    if (band.nodataCount == band.values.size())
        throw Error("'" + path + "' holds no heights: every cell is nodata");
    Dem dem = openDem(path, heights);
    dem.band.values = std::move(band.values);
    dem.band.nodataCount = band.nodataCount;
    dem.terrain.heightsM = heightsInMetres(dem.band, dem.heights);
    return dem;
}

Dem demFromArray(const Grid<float>& values, const GeoReference& ref, std::optional<double> nodata,
                 const std::string& name, const HeightOptions& heights) {
    if (values.empty()) throw Error("'" + name + "' holds no cells");
    const MemoryRaster file(values, ref, nodata);
    try {
        Dem dem = loadDem(file.path(), heights);
        dem.band.path = name;
        return dem;
    } catch (const Error& e) {
        // The messages name the file the values passed through; the caller knows them by `name`.
        std::string message = e.what();
        for (auto at = message.find(file.path()); at != std::string::npos; at = message.find(file.path(), at + name.size()))
            message.replace(at, file.path().size(), name);
        throw Error(message);
    }
}

std::pair<double, double> cellLatLon(const Dem& dem, double col, double row) {
    const auto& gt = dem.band.ref.geoTransform;
    double x = gt[0] + col * gt[1];
    double y = gt[3] + row * gt[5];
    if (dem.crs.geographic) return {y, x};
    double lat = 0, lon = 0;
    if (!dem.toLatLon || !dem.toLatLon->apply(x, y, lat, lon))
        throw Error("cannot find latitude/longitude of a point of '" + dem.band.path + "'");
    return {lat, lon};
}

std::pair<double, double> crsPointOfWgs84(const Dem& dem, double latitudeDeg, double longitudeDeg) {
    OGRSpatialReference wgs84, grid;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // lon, lat
    grid.importFromWkt(dem.band.ref.crsWkt.c_str());
    grid.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    TransformPtr toGrid(OGRCreateCoordinateTransformation(&wgs84, &grid));
    double x = longitudeDeg, y = latitudeDeg;
    if (!toGrid || !toGrid->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y))
        throw Error("cannot place latitude " + std::to_string(latitudeDeg) + ", longitude " +
                    std::to_string(longitudeDeg) + " in the CRS of '" + dem.band.path + "'");
    return {x, y};
}

}  // namespace demlight
