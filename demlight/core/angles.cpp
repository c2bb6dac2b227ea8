#include "demlight/core/angles.h"

namespace demlight {

double wrapAzimuthDeg(double azimuthDeg) {
    double a = std::fmod(azimuthDeg, 360.0);
    if (a < 0) a += 360.0;
    if (a >= 360.0 || a == 0.0) a = 0.0;  // also turns -0.0 into +0.0
    return a;
}

double southBasedAzimuthDeg(double azimuthDeg) { return wrapAzimuthDeg(azimuthDeg) - 180.0; }

}  // namespace demlight
