// A DEM as products read it: opened once, read by window. Today the whole DEM is held in
// memory and a window is cut from it; the interface is the one a streamed source will keep.
#pragma once

#include "geo/dem.h"
#include "src/grid.h"

#include <memory>
#include <string>

namespace demlight {

class DemSource {
public:
    /// Opens any path GDAL opens (band 1) and reads its heights in metres (loadDem).
    static DemSource open(const std::string& path, const HeightOptions& heights = {});
    /// A DEM already in memory (tests, bindings).
    explicit DemSource(Dem dem);

    /// The whole DEM.
    const Dem& dem() const { return *dem_; }
    const std::string& path() const { return dem_->band.path; }
    std::size_t width() const { return dem_->terrain.width(); }
    std::size_t height() const { return dem_->terrain.height(); }
    /// The window of every cell.
    CellWindow whole() const { return {0, 0, width(), height()}; }
    bool isWhole(const CellWindow& w) const;
    /// Throws Error naming the window unless it is non-empty and inside the DEM.
    void checkWindow(const CellWindow& w) const;
    /// `w` grown by haloCells on every side, clipped to the DEM.
    CellWindow withHalo(const CellWindow& w, std::size_t haloCells) const;
    /// The window as a DEM of its own: heights, per-row geometry (cropTerrain), and the
    /// georeference of the window's corner.
    Dem read(const CellWindow& w) const;

private:
    std::shared_ptr<const Dem> dem_;
    std::shared_ptr<const GridFrame> frame_;  ///< the whole DEM as the full grid of its windows
};

}  // namespace demlight
