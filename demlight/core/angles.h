// Degree/radian helpers shared by every module.
#pragma once

#include <cmath>
#include <numbers>

namespace demlight {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;
inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;

/// Wraps an azimuth (degrees) into [0, 360); 360 and -0 map to 0 exactly.
double wrapAzimuthDeg(double azimuthDeg);

/// A true azimuth (degrees clockwise from north) counted from south instead, as PVGIS's horizon
/// and plane azimuths are (0 = south, 90 = west, -90 = east), in [-180, 180): north is -180.
double southBasedAzimuthDeg(double azimuthDeg);

}  // namespace demlight
