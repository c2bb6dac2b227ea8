// Irradiance in W m-2 on each cell's inclined surface at one instant: the ESRA clear sky
// (demlight/lighting/esra.h) lit through demlight's geometry, the sun-disk visibility and Lambert term of
// the sun frame (demlight/lighting/sun_frame.h) and the visible sky from the horizons (demlight/lighting/sky.h).
//
//   beam      = B0c O max(0, N.s)                              both models
//             (E6 times Hoffman & Mitchell 2001b, Eq. 3)
//   visible-sky (demlight): the sky and the ground are the two parts of the normal hemisphere,
//             split by the horizon raised to the horizontal, max(h, 0):
//     diffuse   = Dhc K0                                       isotropic sky of radiance Dhc / pi
//     reflected = albedo Ghc (1 - K0)                          ground of radiance albedo Ghc / pi
//             with K0 the Lambert-weighted visible sky above the horizontal (sky K of horizons
//             max(h, 0)): 1 on open flat ground, (1 + cos g)/2 on an open plane of slope g, so on
//             open ground this is the isotropic (Liu & Jordan) model, and terrain that hides sky
//             moves its share from diffuse to reflected. Ghc is the clear-sky global horizontal.
//   rsun (r.sun's own): diffuse from Muneer's tilted-surface model (E10-E11) with the shadow
//             test replaced by the disk visibility O; reflected = albedo (O Bhc + Dhc)(1 - cos g)/2
//             (E12 with r.sun's Ghc: no beam on a shadowed cell). No horizons beyond the sun's.
#pragma once

#include "demlight/lighting/esra.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/grid.h"
#include "demlight/core/sun_field.h"

#include <array>
#include <string_view>

namespace demlight {

/// How diffuse and ground-reflected irradiance reach a tilted, partly hidden cell.
enum class DiffuseModel { VisibleSky, RSun };
/// "visible-sky" or "rsun"; throws FieldError "diffuseModel" naming the choices.
DiffuseModel parseDiffuseModel(std::string_view name);
std::string_view diffuseModelName(DiffuseModel model);

struct IrradianceParams {
    DiffuseModel model = DiffuseModel::VisibleSky;
    double linke = kDefaultLinke;      ///< Linke turbidity factor (air mass 2)
    double albedo = 0;                 ///< ground albedo (0-1)
    double coeffBh = 1, coeffDh = 1;   ///< real-sky beam and diffuse indices (0-1)
    double extraterrestrialWm2 = kSolarConstantWm2;  ///< G0 (E1)
};

/// What one cell sees: the sun terms of the sun frame and the visible sky.
struct CellView {
    double sunIrradiance = 0;  ///< O max(0, N.s), normalised (demlight/lighting/sun.h)
    double sunVisibility = 0;  ///< O, the visible fraction of the disk
    TiltedSurface surface;     ///< slope and incidence (rsun model)
    double skyK0 = 1;          ///< visible sky above the horizontal (visible-sky model)
};

/// The horizons of the visible-sky split: max(h, 0) per cell, NaN kept (K0 is sky K on these).
void raiseToHorizontal(const Grid<float>& horizonDeg, Grid<float>& raised);

/// The three components of one cell (W m-2); global is their sum.
struct CellIrradiance {
    double beam = 0, diffuse = 0, reflected = 0;
    double global() const { return beam + diffuse + reflected; }
};

/// Per-cell values of the clear-sky inputs that may vary over the DEM (r.sun's linke, albedo,
/// coeff_bh and coeff_dh rasters), each of the DEM's shape; null = the constant of
/// IrradianceParams. A NaN value (the raster has no data there) makes the cell's outputs NaN.
struct ClearSkyGrids {
    const Grid<float>* linke = nullptr;
    /// Linke turbidity per calendar month (January first), all twelve or none, in place of
    /// `linke` over a period: a sun's month picks its grid (SunBin::month in demlight/lighting/insolation.h).
    std::array<const Grid<float>*, 12> linkeByMonth{};
    const Grid<float>* albedo = nullptr;
    const Grid<float>* coeffBh = nullptr;
    const Grid<float>* coeffDh = nullptr;
    bool monthlyLinke() const { return linkeByMonth[0] != nullptr; }
    /// A grid that changes the clear sky itself (not only the albedo) is given.
    bool changesSky() const { return linke || monthlyLinke() || coeffBh || coeffDh; }
    /// `params` with the grids' values at (col, row); false where a grid (a monthly Linke grid
    /// included) holds NaN. A monthly Linke leaves params.linke as it is.
    bool at(std::size_t col, std::size_t row, IrradianceParams& params) const;
};

/// The model above for one cell under the clear sky `sky` of its sun and height.
CellIrradiance cellIrradiance(const ClearSky& sky, const CellView& view, const IrradianceParams& params);
/// The same with the cell's slope terms of the rsun model (muneerSlope(view.surface.normalUp))
/// given, for drivers that evaluate many suns at one cell: the same bits.
CellIrradiance cellIrradiance(const ClearSky& sky, const CellView& view, const IrradianceParams& params,
                              const MuneerSlope& slope);

/// Grids of the DEM's shape; NaN at nodata.
struct IrradianceMaps {
    Grid<float> beam, diffuse, reflected, global;
};

/// The inputs of computeIrradiance, all of the DEM's shape.
struct IrradianceInputs {
    const Grid<float>* heightsM = nullptr;       ///< elevation of the air mass (E2); NaN = nodata
    const Normals* normals = nullptr;
    const SunField* sun = nullptr;               ///< each cell's sun (forEachSunInRow)
    const Grid<float>* sunVisibility = nullptr;  ///< the sun frame's O
    const Grid<float>* sunIrradiance = nullptr;  ///< the sun frame's O max(0, N.s)
    const Grid<float>* skyK0 = nullptr;          ///< visible-sky model only
    ClearSkyGrids grids;                         ///< per-cell Linke, albedo and real-sky indices
};

/// cellIrradiance for every cell, parallel over rows; the same bits for any thread count and for
/// a tile of a DEM (its SunField read through SunField::onTile). Throws Error on missing inputs
/// or mismatched shapes.
IrradianceMaps computeIrradiance(const IrradianceInputs& inputs, const IrradianceParams& params);

}  // namespace demlight
