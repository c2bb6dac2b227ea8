#include "geo/sun_field.h"

#include <algorithm>
#include <cmath>

namespace demlight {
SunField computeSunField(const Dem& dem, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells) {
    const Terrain& terrain = dem.terrain;
    const std::size_t w = terrain.width(), h = terrain.height();
    double sum = 0;
    std::size_t n = 0;
    for (float z : terrain.heightsM.values())
        if (!std::isnan(z)) sum += z, ++n;
    const double meanHeight = n ? sum / static_cast<double>(n) : 0.0;

    const auto positionAt = [&](double col, double row) {
        SolarSite s = site;
        std::tie(s.latitudeDeg, s.longitudeDeg) = cellLatLon(dem, col, row);
        const auto c = std::min(static_cast<std::size_t>(col), w - 1);
        const auto r = std::min(static_cast<std::size_t>(row), h - 1);
        const float z = terrain.heightsM(c, r);
        s.elevationM = std::isnan(z) ? meanHeight : z;
        return solarPosition(s, t, options);
    };

    SunField f;
    f.stepCells = stepCells;
    const SolarPosition centre = positionAt(0.5 * static_cast<double>(w), 0.5 * static_cast<double>(h));
    f.centreAzimuthDeg = centre.azimuthDeg;
    f.centreElevationDeg = centre.elevationDeg;
    const std::size_t ni = (w - 1) / stepCells + 2, nj = (h - 1) / stepCells + 2;
    f.azimuthDeg = Grid<float>(ni, nj);
    f.elevationDeg = Grid<float>(ni, nj);
    for (std::size_t j = 0; j < nj; ++j) {
        for (std::size_t i = 0; i < ni; ++i) {
            const double col = static_cast<double>(std::min(i * stepCells, w - 1)) + 0.5;
            const double row = static_cast<double>(std::min(j * stepCells, h - 1)) + 0.5;
            const SolarPosition p = positionAt(col, row);
            // Unwrap around the centre azimuth.
            double az = p.azimuthDeg;
            while (az - f.centreAzimuthDeg > 180.0) az -= 360.0;
            while (az - f.centreAzimuthDeg < -180.0) az += 360.0;
            f.azimuthDeg(i, j) = static_cast<float>(az);
            f.elevationDeg(i, j) = static_cast<float>(p.elevationDeg);
        }
    }
    return f;
}

}  // namespace demlight
