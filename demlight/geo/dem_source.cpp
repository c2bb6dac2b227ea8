#include "demlight/geo/dem_source.h"

#include "demlight/geo/opening_cache.h"

#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

namespace demlight {

namespace {

/// Cells per strip of the opening pass: ~64 MB of raw values and heights together.
constexpr std::size_t kStripCells = std::size_t{8} << 20;
std::size_t stripRowsFor(std::size_t width) { return std::max<std::size_t>(1, kStripCells / width); }

/// The DEM without its heights, its terrain framed by `frame`.
Dem geometryOf(Dem dem, const std::shared_ptr<const GridFrame>& frame) {
    dem.band.values = Grid<float>();
    dem.band.width = frame->width;
    dem.band.height = frame->height;
    dem.terrain.heightsM = Grid<float>();
    dem.terrain.frame = frame;
    dem.terrain.frameCol0 = dem.terrain.frameRow0 = 0;
    return dem;
}

/// Running extremes and mean of valid heights, in the order a whole-grid pass visits them.
struct HeightStats {
    float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
    double sum = 0;
    std::size_t valid = 0;
    void add(const Grid<float>& heightsM) {
        const auto [l, h] = heightRangeM(heightsM);
        lo = std::min(lo, l), hi = std::max(hi, h);
        for (float z : heightsM.values())
            if (!std::isnan(z)) sum += z, ++valid;
    }
    double mean() const { return valid ? sum / static_cast<double>(valid) : 0.0; }
};

std::size_t nodeCount(std::size_t cells, std::size_t step) { return (cells - 1) / step + 2; }

/// The node heights from a row reader (row -> heights of that row).
template <class RowFn>
NodeHeights nodeHeightsFromRows(std::size_t w, std::size_t h, std::size_t step, double meanM, const RowFn& rowOf) {
    NodeHeights z;
    z.meanM = meanM;
    const std::size_t ni = nodeCount(w, step), nj = nodeCount(h, step);
    z.nodesM = Grid<float>(ni, nj);
    for (std::size_t j = 0; j < nj; ++j) {
        const auto& row = rowOf(std::min(j * step, h - 1));
        for (std::size_t i = 0; i < ni; ++i) z.nodesM(i, j) = row[std::min(i * step, w - 1)];
    }
    const auto centreCol = std::min(static_cast<std::size_t>(0.5 * static_cast<double>(w)), w - 1);
    const auto centreRow = std::min(static_cast<std::size_t>(0.5 * static_cast<double>(h)), h - 1);
    z.centreM = rowOf(centreRow)[centreCol];
    return z;
}

}  // namespace

NodeHeights nodeHeights(const Grid<float>& heightsM, std::size_t stepCells) {
    HeightStats stats;
    stats.add(heightsM);
    return nodeHeightsFromRows(heightsM.width(), heightsM.height(), stepCells, stats.mean(),
                               [&](std::size_t row) { return &heightsM(0, row); });
}

struct DemSource::Derived {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const void>> values;
    std::size_t bytes = 0;
};

std::shared_ptr<const void> DemSource::findDerived(const std::string& key) const {
    std::lock_guard lock(derived_->mutex);
    const auto it = derived_->values.find(key);
    return it == derived_->values.end() ? nullptr : it->second;
}

void DemSource::keepDerived(const std::string& key, std::size_t bytes, std::shared_ptr<const void> value) const {
    std::lock_guard lock(derived_->mutex);
    if (derived_->bytes + bytes > kDerivedBytes) return;
    if (derived_->values.try_emplace(key, std::move(value)).second) derived_->bytes += bytes;
}

NodeHeights DemSource::nodeHeights(std::size_t stepCells) const {
    const std::size_t nodes = nodeCount(width(), stepCells) * nodeCount(height(), stepCells);
    return *derived<NodeHeights>("node heights every " + std::to_string(stepCells), nodes * sizeof(float), [&] {
        if (held_) {
            const Grid<float>& z = held_->terrain.heightsM;
            return nodeHeightsFromRows(width(), height(), stepCells, meanHeightM_,
                                       [&](std::size_t row) { return &z(0, row); });
        }
        return nodeHeightsFromRows(width(), height(), stepCells, meanHeightM_,
                                   [&](std::size_t row) { return heightsM({0, row, width(), row + 1}).values(); });
    });
}

namespace {

/// The pass over the heights in strips of rows: their range, valid count and mean, and the
/// share of steep steps.
OpeningPass passOverHeights(const std::string& path, const Dem& dem, const ProgressFn& progress) {
    const std::size_t width = dem.band.width, height = dem.band.height;
    HeightStats stats;
    SteepSteps steps;
    const std::size_t stripRows = stripRowsFor(width);
    for (std::size_t row0 = 0; row0 < height; row0 += stripRows) {
        const CellWindow strip{0, row0, width, std::min(height, row0 + stripRows)};
        const Grid<float> rows = heightsInMetres(readRasterWindow(path, strip), path, dem.heights);
        stats.add(rows);
        steps.add(rows, row0, dem.terrain.cellWidthM, dem.terrain.cellHeightM);
        if (progress && stripRows < height &&
            !progress(static_cast<double>(strip.row1) / static_cast<double>(height), "reading DEM"))
            throw Cancelled();
    }
    return {width, height, stats.lo, stats.hi, stats.valid, stats.mean(), steps.share()};
}

}  // namespace

DemSource DemSource::open(const std::string& path, const HeightOptions& heights, const ProgressFn& progress,
                          const OpeningCache& cache) {
    Dem dem = openDem(path, heights, progress);
    const std::size_t width = dem.band.width, height = dem.band.height;
    std::optional<OpeningPass> pass = cache.find(path, heights);
    if (pass && (pass->width != width || pass->height != height)) pass.reset();
    if (!pass) {
        pass = passOverHeights(path, dem, progress);
        if (pass->validCells > 0) cache.keep(path, heights, *pass);
    }
    if (pass->validCells == 0) throw Error("'" + path + "' holds no heights: every cell is nodata");
    DemSource s;
    s.derived_ = std::make_shared<Derived>();
    const Terrain& t = dem.terrain;
    s.frame_ = std::make_shared<const GridFrame>(GridFrame{width, height, t.cellWidthM, t.cellHeightM, t.convergence,
                                                           pass->lowM, pass->highM, pass->steepStepShare});
    s.meanHeightM_ = pass->meanHeightM;
    s.validCells_ = pass->validCells;
    dem.band.nodataCount = width * height - pass->validCells;
    s.geometry_ = geometryOf(std::move(dem), s.frame_);
    return s;
}

DemSource DemSource::openWithoutHeightPass(const std::string& path, const HeightOptions& heights,
                                           const ProgressFn& progress) {
    Dem dem = openDem(path, heights, progress);
    DemSource s;
    s.derived_ = std::make_shared<Derived>();
    const Terrain& t = dem.terrain;
    const HeightStats none;  // lo = +inf > hi = -inf: no range known
    s.frame_ = std::make_shared<const GridFrame>(
        GridFrame{dem.band.width, dem.band.height, t.cellWidthM, t.cellHeightM, t.convergence, none.lo, none.hi});
    s.geometry_ = geometryOf(std::move(dem), s.frame_);
    return s;
}

DemSource::DemSource(Dem dem) : derived_(std::make_shared<Derived>()) {
    // The DEM given is the whole grid, even when it was cut from a larger one.
    dem.terrain.frame.reset();
    dem.terrain.frameCol0 = dem.terrain.frameRow0 = 0;
    frame_ = frameOf(dem.terrain);
    HeightStats stats;
    stats.add(dem.terrain.heightsM);
    meanHeightM_ = stats.mean();
    validCells_ = stats.valid;
    held_ = std::make_shared<const Dem>(dem);
    geometry_ = geometryOf(std::move(dem), frame_);
}

bool DemSource::isWhole(const CellWindow& w) const {
    return w.col0 == 0 && w.row0 == 0 && w.col1 == width() && w.row1 == height();
}

void DemSource::checkWindow(const CellWindow& w) const {
    if (!(w.col0 < w.col1 && w.row0 < w.row1 && w.col1 <= width() && w.row1 <= height()))
        throw Error("window columns " + std::to_string(w.col0) + ".." + std::to_string(w.col1) + ", rows " +
                    std::to_string(w.row0) + ".." + std::to_string(w.row1) + " is empty or outside the " +
                    std::to_string(width()) + " x " + std::to_string(height()) + " DEM");
}

CellWindow DemSource::withHalo(const CellWindow& w, std::size_t haloCells) const {
    return {w.col0 - std::min(w.col0, haloCells), w.row0 - std::min(w.row0, haloCells),
            std::min(width(), w.col1 + std::min(haloCells, width())),
            std::min(height(), w.row1 + std::min(haloCells, height()))};
}

void DemSource::readCells(const CellWindow& w, Grid<float>& raw, Grid<float>& heightsM, std::size_t& nodata) const {
    if (held_) {
        raw = cropGrid(held_->band.values, w);
        heightsM = cropGrid(held_->terrain.heightsM, w);
        nodata = 0;
        for (float v : heightsM.values()) nodata += std::isnan(v) ? 1 : 0;
        return;
    }
    raw = readRasterWindow(path(), w, &nodata);
    heightsM = heightsInMetres(raw, path(), geometry_.heights);
}

Dem DemSource::read(const CellWindow& w) const {
    checkWindow(w);
    if (held_ && isWhole(w)) return *held_;
    Dem out;
    out.crs = geometry_.crs;
    out.heights = geometry_.heights;
    out.toLatLon = geometry_.toLatLon;
    out.band = geometry_.band;  // header: nodata, scale, offset, unit, path, georeference
    Grid<float> heightsM;
    readCells(w, out.band.values, heightsM, out.band.nodataCount);
    if (isWhole(w)) {
        out.terrain = geometry_.terrain;
        out.terrain.heightsM = std::move(heightsM);
        out.terrain.frame.reset();
        return out;
    }
    auto& gt = out.band.ref.geoTransform;
    gt[0] += static_cast<double>(w.col0) * gt[1];
    gt[3] += static_cast<double>(w.row0) * gt[5];
    out.band.width = w.col1 - w.col0;
    out.band.height = w.row1 - w.row0;
    out.terrain = tileOf(geometry_.terrain, w, frame_, std::move(heightsM));
    return out;
}

std::shared_ptr<const Dem> DemSource::readWhole() const {
    return held_ ? held_ : std::make_shared<const Dem>(read(whole()));
}

Grid<float> DemSource::heightsM(const CellWindow& w) const {
    checkWindow(w);
    Grid<float> raw, heights;
    std::size_t nodata = 0;
    readCells(w, raw, heights, nodata);
    return heights;
}

std::size_t DemSource::stripRows() const { return stripRowsFor(width()); }

double DemSource::passBytes() const {
    constexpr double kBytesPerCell = 12;
    return static_cast<double>(std::min(stripRows(), height())) * static_cast<double>(width()) * kBytesPerCell;
}

}  // namespace demlight
