#include "geo/dem_source.h"

#include "src/error.h"

#include <algorithm>
#include <cmath>

namespace demlight {

DemSource DemSource::open(const std::string& path, const HeightOptions& heights) {
    return DemSource(loadDem(path, heights));
}

DemSource::DemSource(Dem dem)
    : dem_(std::make_shared<const Dem>(std::move(dem))), frame_(frameOf(dem_->terrain)) {}

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

Dem DemSource::read(const CellWindow& w) const {
    checkWindow(w);
    if (isWhole(w)) return *dem_;
    const std::size_t cols = w.col1 - w.col0, rows = w.row1 - w.row0;
    Dem out;
    out.crs = dem_->crs;
    out.toLatLon = dem_->toLatLon;
    out.band.nodata = dem_->band.nodata;
    out.band.path = dem_->band.path;
    out.band.ref = dem_->band.ref;
    auto& gt = out.band.ref.geoTransform;
    gt[0] += static_cast<double>(w.col0) * gt[1];
    gt[3] += static_cast<double>(w.row0) * gt[5];
    out.band.values = Grid<float>(cols, rows);
    for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < cols; ++c) out.band.values(c, r) = dem_->band.values(w.col0 + c, w.row0 + r);
    out.terrain = tileOf(dem_->terrain, w, frame_);
    out.band.nodataCount = 0;
    for (float v : out.terrain.heightsM.values()) out.band.nodataCount += std::isnan(v) ? 1 : 0;
    return out;
}

}  // namespace demlight
