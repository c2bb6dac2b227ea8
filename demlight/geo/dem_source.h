// A DEM as products read it: opened once, read by window. A source opened from a file holds
// the DEM's geometry only (georeference, CRS, per-row cell sizes, convergence, height range) and
// reads each window's heights from the file when asked, so no product holds more of the DEM
// than its window and halo; a source made from a Dem in memory cuts windows from it.
#pragma once

#include "demlight/geo/dem.h"
#include "demlight/geo/opening_cache.h"
#include "demlight/core/grid.h"
#include "demlight/core/progress.h"

#include <memory>
#include <string>
#include <vector>

namespace demlight {

/// What the sun's lattice needs of a DEM's heights (computeSunField): the heights at the nodes
/// of a lattice every `stepCells` cells (node (i, j) at cell (min(i * step, w - 1),
/// min(j * step, h - 1))), at the centre cell (w / 2, h / 2), and the mean valid height.
struct NodeHeights {
    Grid<float> nodesM;
    float centreM = 0;
    double meanM = 0;
};
/// NodeHeights of heights in memory.
NodeHeights nodeHeights(const Grid<float>& heightsM, std::size_t stepCells);

class DemSource {
public:
    /// Opens any path GDAL opens (band 1) for windowed reading: its header and geometry
    /// (openDem), then one pass over its heights in strips of rows for their range, valid count
    /// and mean; the file must stay readable while the source is used. Throws what loadDem
    /// throws (a DEM with no valid cell included). `progress` hears of the opening (openDem) and
    /// of the pass ("reading DEM") when it takes more than one strip (8 Mi cells), and stops
    /// either (Cancelled) by returning false. `cache` keeps the pass's results for later
    /// processes opening the same, unchanged DEM (demlight/geo/opening_cache.h): they skip the pass.
    static DemSource open(const std::string& path, const HeightOptions& heights = {}, const ProgressFn& progress = {},
                          const OpeningCache& cache = OpeningCache::fromEnvironment());
    /// Opens the DEM as `open` does but without the pass over its heights, for callers that read
    /// a few small windows with a search distance of their own (point queries given a distance):
    /// the height range is unknown (frame lowM > highM, the relief of a DEM without heights, so
    /// planned search distances are the smallest cell side), and meanHeightM and validCells are 0.
    /// `progress` hears of the opening (openDem) and may stop it.
    static DemSource openWithoutHeightPass(const std::string& path, const HeightOptions& heights = {},
                                           const ProgressFn& progress = {});
    /// A DEM already in memory (tests, bindings).
    explicit DemSource(Dem dem);

    /// The whole DEM without its heights: band header, CRS, height transform, and the terrain's
    /// per-row cell sizes, latitudes and convergence, with terrain.frame the full grid
    /// (terrain.heightsM and band.values are empty). Planning, halos and the sun's lattice are
    /// sized from it (fullGrid).
    const Dem& geometry() const { return geometry_; }
    /// The full grid every window's terrain is cut from (heights range included).
    const std::shared_ptr<const GridFrame>& frame() const { return frame_; }
    /// The whole DEM when the source holds it in memory (made from a Dem), else null.
    const Dem* held() const { return held_.get(); }
    const std::string& path() const { return geometry_.band.path; }
    std::size_t width() const { return frame_->width; }
    std::size_t height() const { return frame_->height; }
    /// Mean of the valid heights (metres), summed in row order as a whole-DEM pass sums them.
    double meanHeightM() const { return meanHeightM_; }
    /// Cells with a height (not nodata).
    std::size_t validCells() const { return validCells_; }
    /// The window of every cell.
    CellWindow whole() const { return {0, 0, width(), height()}; }
    bool isWhole(const CellWindow& w) const;
    /// Throws Error naming the window unless it is non-empty and inside the DEM.
    void checkWindow(const CellWindow& w) const;
    /// `w` grown by haloCells on every side, clipped to the DEM.
    CellWindow withHalo(const CellWindow& w, std::size_t haloCells) const;
    /// The window as a DEM of its own: heights in metres, raw band values, the georeference of
    /// the window's corner, and a terrain that is a tile of the full grid (tileOf); the whole
    /// window is the DEM as loadDem reads it (no frame).
    Dem read(const CellWindow& w) const;
    /// The whole DEM: the one held, or read (read(whole())).
    std::shared_ptr<const Dem> readWhole() const;
    /// Heights (metres, NaN for nodata) of a window, without the rest of read()'s Dem.
    Grid<float> heightsM(const CellWindow& w) const;
    /// Rows per strip of a pass over the whole DEM (about 8 Mi cells a strip).
    std::size_t stripRows() const;
    /// Memory (bytes) the opening pass over the heights holds at once: a strip's raw values,
    /// heights and the file's decoded blocks, 12 bytes a cell.
    double passBytes() const;
    /// NodeHeights of the whole DEM, read from the rows the nodes lie on (remembered per step:
    /// every instant of a period asks for the same).
    NodeHeights nodeHeights(std::size_t stepCells) const;

    /// A value derived from the whole DEM that every window of a job needs again (the sun's
    /// lattice at an instant, node heights, auxiliary rasters resampled onto the grid): `make`
    /// runs on the first call for `key`, later calls (from any window, any thread) return the
    /// same value. Values are kept while the source lives, up to kDerivedBytes in all (`bytes`
    /// is the value's size); past that a value is made and not kept.
    template <class T, class Make>
    std::shared_ptr<const T> derived(const std::string& key, std::size_t bytes, const Make& make) const {
        if (auto kept = findDerived(key)) return std::static_pointer_cast<const T>(kept);
        auto value = std::make_shared<const T>(make());
        keepDerived(key, bytes, value);
        return value;
    }
    static constexpr std::size_t kDerivedBytes = std::size_t{512} << 20;

private:
    DemSource() = default;
    /// Raw values and heights in metres of a window, from the file or the held DEM.
    void readCells(const CellWindow& w, Grid<float>& raw, Grid<float>& heightsM, std::size_t& nodata) const;

    Dem geometry_;
    std::shared_ptr<const Dem> held_;
    std::shared_ptr<const GridFrame> frame_;
    double meanHeightM_ = 0;
    std::size_t validCells_ = 0;
    std::shared_ptr<const void> findDerived(const std::string& key) const;
    void keepDerived(const std::string& key, std::size_t bytes, std::shared_ptr<const void> value) const;
    struct Derived;
    std::shared_ptr<Derived> derived_;  ///< shared by copies of the source
};

}  // namespace demlight
