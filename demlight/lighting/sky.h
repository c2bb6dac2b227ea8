// Sky factors from horizon angles: the sky-view factors GIS users know, the Lambert-weighted
// visible sky K(p) and the interreflection sky factor f_sky of Hoffman & Mitchell (2001b,
// Eq. 8-12, after Stewart & Langer 1997), and sky patches.
//
// Sector convention: D horizon angles h_i (degrees, may be negative) are given for the true
// azimuths phi_i = i * 360 / D (degrees clockwise from true north). Sector i is the azimuth
// interval [phi_i - 180/D, phi_i + 180/D) and the horizon is taken as constant h_i across it.
// Directions are ENU unit vectors v = (sin az cos el, cos az cos el, sin el).
//
// Normal hemisphere: K counts only directions with N.v > 0. Each sector's horizon is clamped
// to the tangent plane of the cell EXACTLY, i.e. per azimuth inside the sector (the plane's
// elevation varies across the sector), not at the sector centre: the clamped region is
// integrated in closed form (see sky.cpp). Consequently a tilted plane with no terrain above
// it gets K = 1 for every D, and flat ground with h <= 0 gets K = 1.
#pragma once

#include "demlight/lighting/sun.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace demlight {

/// A direction or normal in the local East-North-Up frame (unit length unless stated).
using EnuVector = Enu;

/// Normals whose up component is below this are treated as having this up component (a height
/// field's normal always points up; this only guards degenerate input).
inline constexpr double kMinNormalUp = 1e-6;

/// Error budget of the default direction count (mean absolute error against the dense
/// reference on real DEMs, tests/sky_realdem_test.cpp): svf_horizontal and sky_K.
inline constexpr double kSkyBudgetMae = 0.003;
/// The same for sky_factor with albedo C = 0.2.
inline constexpr double kSkyFactorBudgetMae = 0.005;

/// Default number of sweep directions (sectors) for sky factors and apertures (`demlight sky`,
/// `demlight aperture`, `demlight sun --model aperture*`).
/// Rule: the smallest D of 4, 8, 16, 32, 64 whose MAE against the dense reference
/// (tests/sky_realdem_test.cpp: 300 non-truncated cells, 360 reference azimuths) meets
/// kSkyBudgetMae for svf_horizontal and sky_K and kSkyFactorBudgetMae for sky_factor (C = 0.2)
/// on all three test DEMs (the measured table:
/// docs/measurements.md#lightingskyh-kdefaultskydirections). At D >= 16 the svf_horizontal
/// error is mostly the sweep's horizon error, so more directions barely help it.
inline constexpr std::size_t kDefaultSkyDirections = 16;

// ---- Per-cell kernels (D = horizonDeg.size() >= 1) ------------------------------------------

/// Sky-view factor of a horizontal plane, cosine weighted (Dozier & Frew 1990):
/// 1 - mean_i sin^2(max(h_i, 0)). Dimensionless in [0, 1].
double svfHorizontal(std::span<const float> horizonDeg);

/// Unweighted visible sky fraction (Zaksek et al. 2011, RVT "SVF"): 1 - mean_i sin(max(h_i, 0)).
double skyFraction(std::span<const float> horizonDeg);

/// K(p) = (1/pi) * integral over visible sky within the normal hemisphere of N.v d(omega)
/// (Hoffman & Mitchell 2001b, Eq. 9), integrated exactly for a piecewise-constant horizon over D
/// sectors (generalises Eq. 10-12). `normal` is the cell's unit ENU normal. In [0, 1].
double skyK(std::span<const float> horizonDeg, const EnuVector& normal);

/// Contribution to K of the directions with azimuth in [az0Deg, az1Deg] (az1Deg >= az0Deg,
/// width <= 360) and elevation in [max(horizonDeg, bandLowDeg), bandHighDeg], clipped to the
/// normal hemisphere. Exact closed form. The building block of skyK and the patch factors.
double skyKWedge(const EnuVector& normal, double az0Deg, double az1Deg, double horizonDeg,
                 double bandLowDeg = -90.0, double bandHighDeg = 90.0);

/// Interreflection sky factor f_sky = K / (1 - C (1 - K)) (Hoffman & Mitchell 2001b, Eq. 8, after
/// Stewart & Langer 1997). albedo C is clamped to [0, 1] and K to [0, 1]. Limits: K = 0 gives 0 for
/// any C (no sky, no light enters; the C = 1, K = 0 corner is 0/0 and is defined as 0); C = 1 with
/// K > 0 gives 1; C = 0 gives K. The denominator is >= K, so no division by zero for K > 0.
double skyFactor(double skyK, double albedo);

/// skyFactor of every cell of a K grid, with the albedo of each cell (`albedo`) or one for all;
/// NaN where K or the albedo is NaN, as SkyAccumulator::finish gives it. For a K made otherwise
/// than by one accumulator (canopy blends).
Grid<float> skyFactorOf(const Grid<float>& skyK, const Grid<float>* albedo, double constantAlbedo);

// ---- Sky patches -----------------------------------------------------------------------------

/// One sky patch: azimuths [azimuth0Deg, azimuth1Deg) (azimuth0Deg may be negative, e.g. a
/// north wedge -45..45) times elevations [elevation0Deg, elevation1Deg].
struct SkyPatch {
    double azimuth0Deg = 0.0;
    double azimuth1Deg = 360.0;
    double elevation0Deg = -90.0;
    double elevation1Deg = 90.0;
    std::string name;  ///< e.g. "az -45..45 el -90..45"
};

/// A partition of the sphere of directions into patches: the patch K values sum to K.
struct SkyPatches {
    std::vector<SkyPatch> patches;
    std::string spec;  ///< the spec string the patches were parsed from
    bool empty() const { return patches.empty(); }
    std::size_t size() const { return patches.size(); }
};

/// Parses a patch spec (the `--patches` option):
///   "sky"                       one patch, the whole sky (patch K = K)
///   "sectors:N"                 N equal azimuth wedges, the first centred on true north
///                               (sectors:4 -> N, E, S, W wedges of 90 degrees)
///   "bands:E0,E1,...,En"        elevation bands (degrees), strictly increasing, En = 90,
///                               E0 in [-90, 90); the first band reaches down to -90 (all sky
///                               below E1, negative horizons included) so that the patches
///                               still sum to K, and its name says so ("el -90..E1")
///   "sectors:N,bands:E0,...,En" both; patch index = sector * bands + band
/// Whitespace is ignored. Throws Error naming the offending part and what was expected.
SkyPatches parseSkyPatches(std::string_view spec);

/// K of every patch for one cell; out.size() must equal patches.size().
void skyPatchK(std::span<const float> horizonDeg, const EnuVector& normal,
               const SkyPatches& patches, std::span<double> out);

// ---- Dense reference -------------------------------------------------------------------------

/// Continuous-horizon quantities of one cell, computed by the dense reference.
struct SkyReference {
    double skyK = 0.0;           ///< K(p)
    double svfHorizontal = 0.0;  ///< 1 - mean sin^2 max(h, 0)
    double skyFraction = 0.0;    ///< 1 - mean sin max(h, 0)
    double solidAngleSr = 0.0;   ///< visible solid angle within the normal hemisphere (sr)
    EnuVector bentNormal;        ///< normalised mean visible direction (normal if none visible)
};

/// Reference integration for a continuous horizon function h(azimuthDeg) (degrees): midpoint
/// quadrature over `azimuthSamples` equal azimuth steps, exact integration in elevation with
/// the lower limit max(h(az), tangent-plane elevation(az)) at each sample. Used to measure the
/// error of the D-sector kernels.
SkyReference referenceSky(const std::function<double(double azimuthDeg)>& horizonDeg,
                          const EnuVector& normal, int azimuthSamples = 1024);

// ---- Grid drivers ----------------------------------------------------------------------------

/// Output grids of the sky drivers. NaN where any input (a horizon or the normal) is NaN.
struct SkyMaps {
    Grid<float> svfHorizontal;    ///< cosine-weighted SVF of the horizontal plane (Dozier)
    Grid<float> skyFraction;      ///< unweighted visible sky fraction (Zaksek / RVT)
    Grid<float> skyK;             ///< K(p), Lambert-weighted visible sky in the normal hemisphere
    Grid<float> skyFactor;        ///< f_sky = K / (1 - C(1 - K))
    std::vector<Grid<float>> patchK;  ///< one grid per patch (empty without patches)
};

/// Streams horizon grids one direction at a time so callers never hold all D grids.
/// Memory: (3 + patches) floats per cell (bytesPerCell). Results are bit-identical for any thread count;
/// every direction must be added exactly once (in any order; the order changes only rounding).
/// The normal grids are referenced, not copied: they must outlive the accumulator.
class SkyAccumulator {
public:
    SkyAccumulator(const Grid<float>& normalEast, const Grid<float>& normalNorth,
                   const Grid<float>& normalUp, std::size_t directions, SkyPatches patches = {});

    /// Adds direction `index` (azimuth index * 360 / D, degrees) whose horizon angles
    /// (degrees, NaN = nodata) are `horizonDeg`. Throws Error on a wrong shape, an index out of
    /// range or a direction added twice.
    void addDirection(std::size_t index, const Grid<float>& horizonDeg);
    /// The same with the accumulator's cells at `cells` of a larger horizon grid (a tile's
    /// window inside the grid swept with its halo); `cells` must match the normals' size.
    void addDirection(std::size_t index, const Grid<float>& horizonDeg, const CellWindow& cells);

    /// Final grids with a constant albedo C in [0, 1]. Throws Error if a direction is missing.
    SkyMaps finish(double albedo) const&;
    /// Final grids with a per-cell albedo raster (NaN albedo gives NaN f_sky only).
    SkyMaps finish(const Grid<float>& albedo) const&;
    /// The same from an accumulator that is done with: its sums become the output grids in
    /// place, so only f_sky needs new memory (fresh pages are slow to fault in;
    /// docs/measurements.md#lightingskyh-skyaccumulatorfinish).
    SkyMaps finish(double albedo) &&;
    SkyMaps finish(const Grid<float>& albedo) &&;

    std::size_t directions() const { return directions_; }
    /// Bytes of sums held per cell with `patches` sky patches.
    static std::size_t bytesPerCell(std::size_t patches) { return (3 + patches) * sizeof(float); }

private:
    /// Turns sums (maps.skyK, maps.skyFraction, maps.svfHorizontal and maps.patchK hold
    /// sumK_, sumSin_, sumSin2_ and sumPatch_, or copies) into the outputs, in place.
    void finishInPlace(SkyMaps& maps, const Grid<float>* albedo, double constantAlbedo) const;
    SkyMaps copiedSums() const;
    SkyMaps movedSums();

    const Grid<float>& east_;
    const Grid<float>& north_;
    const Grid<float>& up_;
    std::size_t directions_;
    SkyPatches patches_;
    std::vector<bool> added_;
    /// Per row, the span whose outside addDirection last set to NaN in every sum (all of the
    /// row: nothing set yet). NaN plus anything stays NaN, so a direction whose row has the same
    /// span need not set it again.
    std::vector<RowSpan> nanOutside_;
    // Float sums: a few dozen terms each, so rounding stays near 1e-6, far below the method's
    // error, and half the memory traffic of doubles (the accumulation is bandwidth-bound on
    // large DEMs).
    Grid<float> sumK_;
    Grid<float> sumSin_;
    Grid<float> sumSin2_;
    std::vector<Grid<float>> sumPatch_;
};

/// Convenience driver over all D grids at once (horizonsDeg[i] is azimuth i * 360 / D).
SkyMaps computeSky(const std::vector<const Grid<float>*>& horizonsDeg,
                   const Grid<float>& normalEast, const Grid<float>& normalNorth,
                   const Grid<float>& normalUp, double albedo, const SkyPatches& patches = {});

}  // namespace demlight
