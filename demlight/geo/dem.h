// A DEM opened for lighting: the raster band, its CRS facts, and the Terrain (heights plus
// per-row metric cell sizes and meridian convergence) the lighting kernels consume.
#pragma once

#include "demlight/geo/raster.h"
#include "demlight/core/progress.h"
#include "demlight/core/terrain.h"

#include <memory>
#include <optional>
#include <string>

namespace demlight {

/// What demlight needs to know about a CRS.
struct CrsInfo {
    std::string name;
    std::optional<int> epsg;
    bool geographic = false;
    /// Projected CRSs: metres per linear unit of the CRS (1 for metre grids).
    double linearUnitM = 1.0;
    /// Ellipsoid of the CRS (metres, and inverse flattening; 0 for a sphere).
    double semiMajorM = 6378137.0;
    double inverseFlattening = 298.257223563;
};

/// Converts grid coordinates of a projected DEM to latitude/longitude (opaque; GDAL inside).
class LatLonTransform;

/// How to turn a DEM band's values into heights in metres (the DEM's own scale/offset and unit
/// unless overridden).
struct HeightOptions {
    /// Vertical unit to assume instead of the band's own (e.g. "ft"); empty = the band's.
    std::string zUnit;
    /// Multiply heights (after scale and offset) by this instead of converting a unit (metres per
    /// height unit); 0 = not set. Excludes zUnit.
    double zFactor = 0;
};

/// What loadDem applied to the band's values: heightM = (value * scale + offset) * toMetres.
struct HeightTransform {
    /// GDAL band scale and offset (the offset is in `unit`).
    double scale = 1;
    double offset = 0;
    /// Vertical unit as the band declares it, or as HeightOptions::zUnit overrides it; empty when
    /// neither names one.
    std::string unit;
    /// Metres per unit.
    double toMetres = 1;
    /// Where toMetres came from: "band", "zUnit option", "zFactor option", or
    /// "default (no unit declared: metres)".
    std::string source;
};

/// Metres per vertical unit for the units demlight knows (case-insensitive): "" and metres (1),
/// international feet (0.3048), US survey feet (1200/3937), cm, dm, mm, km; nullopt otherwise.
std::optional<double> metresPerUnit(const std::string& unit);

struct Dem {
    RasterBand band;
    CrsInfo crs;
    /// Heights in metres (the band's values through `heights`) plus per-row cell sizes and
    /// convergence.
    Terrain terrain;
    /// How the band's values became terrain.heightsM.
    HeightTransform heights;
    /// Set for projected DEMs; shared so Dem stays cheap to copy.
    std::shared_ptr<const LatLonTransform> toLatLon;
};

/// Opens a DEM (any path GDAL opens, /vsizip/ and other virtual paths included): reads band 1,
/// turns its values into metres (band scale and offset, then the band's unit or `heights`),
/// checks the georeferencing, computes per-row metric cell sizes (GeographicLib on the CRS's
/// ellipsoid for geographic CRSs) and the meridian convergence lattice for projected CRSs.
/// Nodata is matched on the raw values, and dem.band keeps the raw values and nodata value.
/// Throws Error on all bad input listed in docs/design.md §9 and on invalid `heights`.
Dem loadDem(const std::string& path, const HeightOptions& heights = {});

/// loadDem of band values held in memory: `values` (raw, NaN or `nodata` for no data) on `ref`
/// (ref.crsWkt: WKT, or a definition such as "EPSG:32610"), read through a MemoryRaster so that
/// every check and conversion of a file applies. `name` stands for the file in the DEM
/// (band.path, DEMLIGHT_INPUT) and in messages.
Dem demFromArray(const Grid<float>& values, const GeoReference& ref, std::optional<double> nodata,
                 const std::string& name, const HeightOptions& heights = {});

/// loadDem without reading the heights: the band's header (band.values empty, band.width and
/// band.height set), CRS, height transform, and the terrain's per-row cell sizes, latitudes and
/// convergence for the whole grid (terrain.heightsM empty). What a streamed source keeps.
/// Refuses a DEM of more than 2^22 cells a side. A projected DEM costs one PROJ call per row and two per convergence node (at most
/// 2^20 nodes, convergenceStepCells); when that is much work `progress` hears of it ("opening
/// DEM") between batches of points, and stops it (Cancelled) by returning false.
Dem openDem(const std::string& path, const HeightOptions& heights = {}, const ProgressFn& progress = {});

/// The spacing (cells) of the convergence lattice of a width x height projected DEM: every 64
/// cells, or the smallest power-of-two multiple of that which keeps the lattice within 2^20
/// nodes, so that a header declaring a vast grid costs no more to open than a 65 000-cell one.
std::size_t convergenceStepCells(std::size_t width, std::size_t height);

/// Raw band values as metres through `tr` (NaN stays NaN; the identity copies the bits); throws
/// Error naming `path` for a value beyond what a float holds.
Grid<float> heightsInMetres(Grid<float> raw, const std::string& path, const HeightTransform& tr);
/// heightsInMetres of the band's values.
Grid<float> heightsInMetres(const RasterBand& band, const HeightTransform& tr);

/// Latitude and longitude (degrees, on the CRS's own datum) of a cell centre.
std::pair<double, double> cellLatLon(const Dem& dem, double col, double row);

/// The DEM's CRS coordinates (x, y) of a WGS84 latitude and longitude (degrees), through PROJ
/// (a datum shift included where the DEM's datum is not WGS84). Throws Error naming the DEM when
/// PROJ cannot transform the point.
std::pair<double, double> crsPointOfWgs84(const Dem& dem, double latitudeDeg, double longitudeDeg);

}  // namespace demlight
