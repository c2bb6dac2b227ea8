// Degree/radian helpers shared by every module.
#pragma once

#include <cmath>
#include <numbers>

namespace demlight {

inline constexpr double kDegToRad = std::numbers::pi / 180.0;
inline constexpr double kRadToDeg = 180.0 / std::numbers::pi;

/// Wraps an azimuth (degrees) into [0, 360); 360 and -0 map to 0 exactly.
double wrapAzimuthDeg(double azimuthDeg);

}  // namespace demlight
