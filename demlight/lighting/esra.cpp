#include "demlight/lighting/esra.h"

#include "demlight/core/angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace demlight {
namespace {

/// E5 switches from the polynomial to the linear fit above this air mass.
constexpr double kRayleighPolynomialMaxAirMass = 20;
/// E6: the Linke factor is given for air mass 2; 0.8662 turns it into Kasten's pyrheliometric form.
constexpr double kLinkeAirMass2Factor = 0.8662;
/// E8: lower bound of A1 Tn.
constexpr double kMinA1Tn = 0.0022;
/// E10: N of shadowed surfaces.
constexpr double kShadowedN = 0.252271;
/// E11: below this solar elevation (radians) the sunlit case uses the low-sun form.
constexpr double kLowSunRad = 0.1;

}  // namespace

double extraterrestrialIrradiance(double earthSunDistanceAu, double solarConstantWm2) {
    return solarConstantWm2 / (earthSunDistanceAu * earthSunDistanceAu);  // E1
}

double esraRefractionDeg(double trueElevationDeg) {
    const double h = trueElevationDeg * kDegToRad;
    return 0.061359 * (0.1594 + h * (1.123 + 0.065656 * h)) / (1 + h * (28.9344 + 277.3971 * h)) * kRadToDeg;  // E3
}

double pressureRatio(double elevationM) { return std::exp(-elevationM / kEsraScaleHeightM); }  // E2

double airMassDenominator(double apparentElevationDeg) {
    return std::sin(apparentElevationDeg * kDegToRad) + 0.50572 * std::pow(apparentElevationDeg + 6.07995, -1.6364);  // E4
}

double relativeAirMass(double apparentElevationDeg, double elevationM) {
    return pressureRatio(elevationM) / airMassDenominator(apparentElevationDeg);  // E4
}

double rayleighOpticalThickness(double m) {
    if (m <= kRayleighPolynomialMaxAirMass)
        return 1 / (6.6296 + m * (1.7513 + m * (-0.1202 + m * (0.0065 - m * 0.00013))));  // E5
    return 1 / (10.4 + 0.718 * m);
}

double beamNormalClearSky(double extraterrestrialWm2, double linke, double airMass) {
    return extraterrestrialWm2 *
           std::exp(-kLinkeAirMass2Factor * linke * airMass * rayleighOpticalThickness(airMass));  // E6
}

double diffuseTransmission(double linke) {
    return -0.015843 + linke * (0.030543 + 0.0003797 * linke);  // E7
}

double diffuseAngular(double linke, double sinElevation) {
    const double tn = diffuseTransmission(linke);
    double a1 = 0.26463 + linke * (-0.061581 + 0.0031408 * linke);  // E8
    if (a1 * tn < kMinA1Tn) a1 = kMinA1Tn / tn;
    const double a2 = 2.04020 + linke * (0.018945 - 0.011161 * linke);
    const double a3 = -1.3025 + linke * (0.039231 + 0.0085079 * linke);
    return a1 + sinElevation * (a2 + a3 * sinElevation);
}

ClearSkySun clearSkySun(double g0, double linke, double apparentElevationDeg, double coeffBh, double coeffDh) {
    ClearSkySun sun;
    sun.extraterrestrial = g0;
    sun.linke = linke;
    sun.coeffBh = coeffBh;
    if (!(apparentElevationDeg > 0)) return sun;
    sun.up = true;
    sun.sinElevation = std::sin(apparentElevationDeg * kDegToRad);
    sun.airMassDenominator = airMassDenominator(apparentElevationDeg);
    sun.diffuseHorizontal = coeffDh * g0 * diffuseTransmission(linke) * diffuseAngular(linke, sun.sinElevation);  // E9
    return sun;
}

ClearSky clearSky(const ClearSkySun& sun, double pressureRatio) {
    if (!sun.up) return clearSkyWithBeam(sun, 0);
    const double airMass = pressureRatio / sun.airMassDenominator;  // E4
    return clearSkyWithBeam(sun, sun.coeffBh * beamNormalClearSky(sun.extraterrestrial, sun.linke, airMass));
}

ClearSky clearSkyWithBeam(const ClearSkySun& sun, double beamNormal) {
    ClearSky out;
    out.extraterrestrial = sun.extraterrestrial;
    if (!sun.up) return out;
    out.beamNormal = beamNormal;
    out.beamHorizontal = beamNormal * sun.sinElevation;  // E6
    out.diffuseHorizontal = sun.diffuseHorizontal;
    return out;
}

BeamNormalTable::BeamNormalTable(const ClearSkySun& sun, double lowM, double highM) : sun_(sun) {
    first_ = std::floor(std::min(lowM, highM) / kStepM);
    const double lastNode = std::max(std::ceil(std::max(lowM, highM) / kStepM), first_ + 1);
    values_.resize(static_cast<std::size_t>(lastNode - first_) + 1);
    for (std::size_t i = 0; i < values_.size(); ++i)
        values_[i] = clearSky(sun, pressureRatio((first_ + static_cast<double>(i)) * kStepM)).beamNormal;
    last_ = static_cast<double>(values_.size() - 2);
    if (sun.up) {
        // E4 with m = kRayleighPolynomialMaxAirMass solved for the elevation (E2).
        const double switchM = -kEsraScaleHeightM * std::log(kRayleighPolynomialMaxAirMass * sun.airMassDenominator);
        const double segment = std::floor(switchM / kStepM) - first_;
        if (segment >= 0 && segment <= last_) switchSegment_ = segment;
    }
}

ClearSky clearSky(double g0, double linke, double apparentElevationDeg, double elevationM, double coeffBh,
                  double coeffDh) {
    return clearSky(clearSkySun(g0, linke, apparentElevationDeg, coeffBh, coeffDh), pressureRatio(elevationM));
}

MuneerSlope muneerSlope(double normalUp) {
    MuneerSlope s;
    s.cosG = std::min(1.0, normalUp);
    if (s.cosG >= 1) return s;  // r.sun's plane case
    const double g = std::acos(s.cosG), sinG = std::sin(g);
    s.rSky = (1 + s.cosG) / 2;
    const double halfSin = std::sin(g / 2);
    s.fg = sinG - g * s.cosG - std::numbers::pi * halfSin * halfSin;  // E10
    return s;
}

double muneerDiffuse(double dhc, double kb, const TiltedSurface& s, double sunlit) {
    return muneerDiffuse(dhc, kb, s, sunlit, muneerSlope(s.normalUp));
}

double muneerDiffuse(double dhc, double kb, const TiltedSurface& s, double sunlit, const MuneerSlope& slope) {
    if (slope.cosG >= 1) return dhc;  // r.sun's plane case
    const double rSky = slope.rSky, fg = slope.fg;
    const double shadowed = rSky + fg * kShadowedN;
    double lit = shadowed;
    const double weight = s.cosIncidence > 0 ? std::clamp(sunlit, 0.0, 1.0) : 0.0;
    if (weight > 0) {
        const double h = s.sunElevationRad;
        const double f = (0.00263 - kb * (0.712 + 0.6883 * kb)) * fg + rSky;  // E10, sunlit N
        lit = h >= kLowSunRad ? f * (1 - kb) + kb * s.cosIncidence / std::sin(h)          // E11
                              : f * (1 - kb) + kb * s.towardSun / (0.1 - 0.008 * h);
    }
    return dhc * (weight * lit + (1 - weight) * shadowed);
}

}  // namespace demlight
