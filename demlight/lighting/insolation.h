// Irradiation totals over a period (Wh m-2) by binned sun positions (docs/design.md §6.8):
// the period's sun positions are put in bins by azimuth sector (the D directions of the sky
// sweeps) and elevation band, each bin keeping its time and its time-weighted mean sun; every
// cell then sums, over the bins, the irradiance of demlight/lighting/irradiance.h at the bin's mean sun
// times the bin's hours, with the horizon of the bin's sector. One sweep per sector serves every
// instant of the period, where an exact integral sweeps once per instant.
//
// What binning changes against the exact integral: a bin's sun is its mean (within one sector,
// 360/D degrees, and one elevation band), its horizon is the one at the sector's centre azimuth,
// and the sun is the one at the DEM centre (one position per instant for the whole DEM).
#pragma once

#include "demlight/lighting/irradiance.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"

#include <cstddef>
#include <limits>
#include <vector>

namespace demlight {

/// The period's sun positions in one azimuth sector and elevation band (and one Linke factor).
struct SunBin {
    std::size_t direction = 0;    ///< azimuth sector: directionAzimuthDeg(direction, directions)
    double hours = 0;             ///< time the sun spends in the bin (hours, integration weights)
    double azimuthDeg = 0;        ///< time-weighted mean true azimuth
    double elevationDeg = 0;      ///< time-weighted mean apparent elevation (> 0)
    double extraterrestrialWm2 = 0;  ///< time-weighted mean G0
    double linke = 0;             ///< the Linke factor of the bin's instants
    /// The calendar month (0 = January) of the bin's instants whose Linke grid applies
    /// (ClearSkyGrids::linkeByMonth), or -1 when the Linke does not vary by month.
    int month = -1;
};

/// One sun position of the period with its integration weight.
struct WeightedSun {
    double hours = 0;  ///< weight (hours)
    double azimuthDeg = 0, elevationDeg = 0, extraterrestrialWm2 = 0, linke = 0;
    int month = -1;  ///< as SunBin::month
};

/// Bins of `suns` (those with elevation > 0) for `directions` azimuth sectors and elevation
/// bands `elevationBandDeg` wide; a bin per (sector, band, Linke factor, month). Sorted by direction.
std::vector<SunBin> binSuns(const std::vector<WeightedSun>& suns, std::size_t directions, double elevationBandDeg);

/// Irradiation totals (Wh m-2) and hours of direct sun (the time of each bin times the sun's
/// visible disk fraction there, as demlight/lighting/sunhours.h counts it per instant).
struct InsolationMaps {
    IrradianceMaps irradiation;
    Grid<float> sunHours;
};

/// A bin's sun disk, for the test that most (cell, bin) pairs pass: the disk wholly above both
/// the horizon and the cell's tangent plane (O = 1, N.s > 0), or wholly below one of them
/// (O = 0); sunTerms() only for the rest. The tangent plane's elevation in the bin's azimuth,
/// atan(across / N_up) (as in sunTerms), is compared through its tangent: across < N_up tan(edge).
/// The tests are strict, so a horizon on an edge (and a point sun, whose edges meet) takes sunTerms.
struct DiskEdges {
    double lowDeg = 0, highDeg = 0;  ///< the disk's lower and upper edge, elevation -+ diameter / 2 (degrees)
    double tanLow = 0, tanHigh = 0;  ///< their tangents (+inf for an upper edge at or above 90 degrees)
};

/// Sums the bins per cell, one sector's horizons at a time. The grids are referenced, not copied.
class InsolationAccumulator {
public:
    /// `params.extraterrestrialWm2` and `params.linke` are ignored: each bin has its own.
    InsolationAccumulator(const Grid<float>& heightsM, const Normals& normals, std::vector<SunBin> bins,
                          std::size_t directions, const IrradianceParams& params, double sunDiameterDeg);
    /// Per-cell Linke, albedo and real-sky indices (grids of the heights' shape, kept by
    /// reference) in place of the params' constants; with a Linke or index grid each cell
    /// evaluates the clear sky of every bin itself instead of the bins' tables.
    void setGrids(const ClearSkyGrids& grids);
    /// Adds the bins of sector `index` with its horizons (degrees, NaN = nodata).
    void addDirection(std::size_t index, const Grid<float>& horizonDeg);
    /// Totals; the visible-sky model takes K0 (demlight/lighting/irradiance.h) here. NaN at nodata.
    InsolationMaps finish(const Grid<float>* skyK0) const;

private:
    /// addDirection for the visible-sky model with constant inputs (the default), per bin of the
    /// sector: its sun, clear sky, beam table and disk edges.
    void addVisibleSky(const Grid<float>& horizonDeg, const std::vector<SunAngles>& angles,
                       const std::vector<ClearSkySun>& skies, const std::vector<BeamNormalTable>& beams,
                       const std::vector<DiskEdges>& edges, const std::vector<const SunBin*>& bins);

    const Grid<float>& heights_;
    const Normals& normals_;
    std::vector<SunBin> bins_;
    std::size_t directions_;
    IrradianceParams params_;
    double sunDiameterDeg_;
    ClearSkyGrids grids_;
    Grid<double> beam_, diffuse_, reflected_, sunHours_;
    /// Valid heights' range: what the bins' BeamNormalTables cover.
    double lowM_ = std::numeric_limits<double>::infinity(), highM_ = -std::numeric_limits<double>::infinity();
};

}  // namespace demlight
