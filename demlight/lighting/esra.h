// Clear-sky irradiance of the European Solar Radiation Atlas model (ESRA; Rigollier, Bauer & Wald
// 2000, "On the clear sky model of the ESRA", Solar Energy 68(1)) as GRASS r.sun implements it
// (Šúri & Hofierka 2004, "A new GIS-based solar radiation model and its application to
// photovoltaic assessments", Transactions in GIS 8(2)), and the tilted-surface diffuse of Muneer
// (1990) as r.sun applies it. Pure per-cell functions; irradiances in W m-2.
//
// Equation labels (E1..E12) are demlight's, listed in docs/outputs.md#irradiance with the paper
// sections they come from:
//   E1  G0 = I0 / R^2                       extraterrestrial irradiance, R the earth-sun distance (AU)
//   E2  p/p0 = exp(-z / 8434.5)             pressure ratio at elevation z (m)
//   E3  dh_ref = 0.061359 (0.1594 + 1.123 h + 0.065656 h^2) / (1 + 28.9344 h + 277.3971 h^2)
//   E4  m = (p/p0) / (sin h_ref + 0.50572 (h_ref_deg + 6.07995)^-1.6364)   (Kasten & Young 1989)
//   E5  dR(m) = 1 / (6.6296 + 1.7513 m - 0.1202 m^2 + 0.0065 m^3 - 0.00013 m^4), m <= 20
//           = 1 / (10.4 + 0.718 m), m > 20                                 (Kasten 1996)
//   E6  B0c = G0 exp(-0.8662 T_LK m dR(m)),  Bhc = B0c sin h
//   E7  Tn = -0.015843 + 0.030543 T_LK + 0.0003797 T_LK^2
//   E8  Fd = A1 + A2 sin h + A3 sin^2 h; A1 = A1', or 0.0022 / Tn where A1' Tn < 0.0022;
//       A1' = 0.26463 - 0.061581 T_LK + 0.0031408 T_LK^2, A2 = 2.04020 + 0.018945 T_LK - 0.011161 T_LK^2,
//       A3 = -1.3025 + 0.039231 T_LK + 0.0085079 T_LK^2
//   E9  Dhc = G0 Tn Fd
//   E10 Muneer: F(g) = r_sky + f_g N, r_sky = (1 + cos g)/2, f_g = sin g - g cos g - pi sin^2(g/2);
//       shadowed N = 0.252271; sunlit N = 0.00263 - 0.712 Kb - 0.6883 Kb^2, Kb = Bhc / (G0 sin h)
//   E11 Dc = Dhc F (shadowed); Dc = Dhc [F (1 - Kb) + Kb cos(i) / sin h] (sunlit, h >= 0.1 rad);
//       Dc = Dhc [F (1 - Kb) + Kb sin g cos(A_sun - A_aspect) / (0.1 - 0.008 h)] (sunlit, h < 0.1 rad)
//   E12 Rc = albedo Ghc (1 - cos g)/2, Ghc = Bhc + Dhc
// h is the solar elevation (radians unless _deg), g the slope, i the incidence angle.
//
// Solar elevation: ESRA takes the true (geometric) elevation and corrects it for refraction (E3)
// before the air mass (E4). demlight's sun positions are SPA's apparent elevations, already
// refracted, so they enter E4 as h_ref directly and E6/E8 as h; esraRefractionDeg (E3) is kept
// for comparisons with r.sun, which computes true elevations.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace demlight {

/// ESRA's and r.sun's solar constant I0 (W m-2).
inline constexpr double kSolarConstantWm2 = 1367.0;
/// r.sun's default Linke turbidity factor (air mass 2), "near the annual average for rural-city
/// areas" (r.sun manual).
inline constexpr double kDefaultLinke = 3.0;
/// Scale height of the pressure ratio (E2, metres).
inline constexpr double kEsraScaleHeightM = 8434.5;

/// E1: extraterrestrial irradiance normal to the sun's rays (W m-2) at earth-sun distance
/// `earthSunDistanceAu` (astronomical units) for solar constant `solarConstantWm2`.
double extraterrestrialIrradiance(double earthSunDistanceAu, double solarConstantWm2 = kSolarConstantWm2);

/// E3: ESRA's refraction correction (degrees) of a true solar elevation `trueElevationDeg`.
double esraRefractionDeg(double trueElevationDeg);

/// E2: pressure ratio p/p0 at `elevationM` metres above sea level.
double pressureRatio(double elevationM);
/// E4's denominator at apparent solar elevation `apparentElevationDeg` (degrees, > 0): the air
/// mass at sea level is its reciprocal.
double airMassDenominator(double apparentElevationDeg);
/// E2 and E4: relative optical air mass at apparent solar elevation `apparentElevationDeg`
/// (degrees, > 0) seen from `elevationM` metres above sea level.
double relativeAirMass(double apparentElevationDeg, double elevationM);

/// E5: Rayleigh optical thickness at air mass `airMass`.
double rayleighOpticalThickness(double airMass);

/// E6: clear-sky beam irradiance normal to the sun's rays (W m-2).
double beamNormalClearSky(double extraterrestrialWm2, double linke, double airMass);

/// E7: diffuse transmission function at zenith.
double diffuseTransmission(double linke);

/// E8: diffuse angular function at a sun of sine elevation `sinElevation`.
double diffuseAngular(double linke, double sinElevation);

/// The clear-sky irradiances of one cell, already multiplied by the real-sky indices.
struct ClearSky {
    double beamNormal = 0;         ///< coeffBh B0c (W m-2)
    double beamHorizontal = 0;     ///< coeffBh Bhc (W m-2)
    double diffuseHorizontal = 0;  ///< coeffDh Dhc (W m-2)
    double extraterrestrial = 0;   ///< G0 (W m-2)
    double globalHorizontal() const { return beamHorizontal + diffuseHorizontal; }
};

/// What clearSky takes of the sun alone, for drivers that evaluate one sun over many cells: all
/// but the air mass's pressure ratio (E2), the one term that depends on the cell's elevation.
struct ClearSkySun {
    bool up = false;                  ///< the sun's centre is above the horizon
    double extraterrestrial = 0;      ///< G0 (W m-2)
    double linke = 0;
    double sinElevation = 0;
    double airMassDenominator = 0;    ///< E4's
    double coeffBh = 1;
    double diffuseHorizontal = 0;     ///< coeffDh Dhc (W m-2), E7-E9
};
ClearSkySun clearSkySun(double extraterrestrialWm2, double linke, double apparentElevationDeg, double coeffBh = 1,
                        double coeffDh = 1);
/// clearSky of `sun` at a cell of pressure ratio `pressureRatio` (E2).
ClearSky clearSky(const ClearSkySun& sun, double pressureRatio);
/// clearSky of `sun` at a cell whose beam normal irradiance coeffBh B0c is `beamNormal`.
ClearSky clearSkyWithBeam(const ClearSkySun& sun, double beamNormal);

/// The beam normal irradiance coeffBh B0c (E2, E4-E6) of one sun as a function of the cell's
/// elevation, for drivers that evaluate one sun over millions of cells: exact at nodes every
/// kStepM metres from sea level and linear between them, but exact in the segment where E5
/// switches fits (m = 20, suns below about 2.5 deg), whose jump no line follows. The nodes are
/// anchored at 0 m, not at the heights the table covers, so every window of a DEM gets the same
/// values. Between nodes the relative error is below 1e-7 (E6's curvature in z;
/// tests/irradiance_test.cpp measures it).
class BeamNormalTable {
public:
    static constexpr double kStepM = 1.0;
    /// Covers elevations lowM..highM (metres); outside them `at` extrapolates the end segment.
    BeamNormalTable(const ClearSkySun& sun, double lowM, double highM);
    double at(double elevationM) const { return at(node(elevationM), elevationM); }

    /// Where an elevation falls among the nodes: found once per cell and read by every table of
    /// the same lowM..highM, which share their nodes.
    struct Node {
        double segment = 0;  ///< start node of the segment (index from the first node)
        double fraction = 0; ///< position within it, 0..1 (beyond at the ends)
    };
    Node node(double elevationM) const {
        const double t = elevationM / kStepM - first_;
        const double i = std::clamp(std::floor(t), 0.0, last_);
        return {i, t - i};
    }
    /// at(elevationM) from node(elevationM) of a table of the same range: the same bits.
    double at(const Node& n, double elevationM) const {
        if (n.segment == switchSegment_) return clearSky(sun_, pressureRatio(elevationM)).beamNormal;
        const auto k = static_cast<std::size_t>(n.segment);
        return values_[k] + n.fraction * (values_[k + 1] - values_[k]);
    }

private:
    ClearSkySun sun_;
    double first_ = 0, last_ = 0;  ///< first node (in steps from 0 m), last segment start index
    double switchSegment_ = -1;    ///< the segment holding E5's switch, or -1
    std::vector<double> values_;
};

/// E4-E9 for a sun at apparent elevation `apparentElevationDeg` seen from `elevationM` metres;
/// all zero when the sun's centre is not above the horizon. coeffBh and coeffDh are r.sun's
/// real-sky indices (clear-sky fractions, 1 = clear).
ClearSky clearSky(double extraterrestrialWm2, double linke, double apparentElevationDeg, double elevationM,
                  double coeffBh = 1, double coeffDh = 1);

/// What the Muneer diffuse (E10, E11) needs of a cell and its sun.
struct TiltedSurface {
    double normalUp = 1;          ///< cos g, the normal's up component
    /// sin g cos(A_sun - A_aspect) = the normal's horizontal part along the sun's azimuth.
    double towardSun = 0;
    double cosIncidence = 0;      ///< N.s, unclamped
    double sunElevationRad = 0;   ///< h (radians, > 0)
};

/// E10-E11: diffuse irradiance on a tilted surface (W m-2) from diffuse horizontal `dhc`, beam
/// index `kb`, and how much of the sun the cell sees, `sunlit` in [0, 1]: r.sun's two cases are
/// 0 (shadowed or facing away) and 1; a partly hidden disk weights them. A horizontal surface
/// (g = 0) gets dhc, as r.sun gives its "plane" case.
double muneerDiffuse(double dhc, double kb, const TiltedSurface& surface, double sunlit);

/// The terms of E10 that depend on the slope g alone, for drivers that evaluate many suns at one
/// cell: muneerDiffuse with them gives the same bits as without.
struct MuneerSlope {
    double cosG = 1;   ///< min(1, normalUp)
    double rSky = 1;   ///< (1 + cos g) / 2
    double fg = 0;     ///< sin g - g cos g - pi sin^2(g/2)
};
MuneerSlope muneerSlope(double normalUp);
double muneerDiffuse(double dhc, double kb, const TiltedSurface& surface, double sunlit, const MuneerSlope& slope);

}  // namespace demlight
