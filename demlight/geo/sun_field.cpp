#include "demlight/geo/sun_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace demlight {

namespace {

/// The field on a w x h grid; `dem` places the nodes (cellLatLon), `z` gives their heights.
SunField sunFieldAtNodes(const Dem& dem, std::size_t w, std::size_t h, const NodeHeights& z, UtcInstant t,
                         const SolarSite& site, const SpaOptions& options, std::size_t stepCells) {
    const auto positionAt = [&](double col, double row, float zM) {
        SolarSite s = site;
        std::tie(s.latitudeDeg, s.longitudeDeg) = cellLatLon(dem, col, row);
        s.elevationM = std::isnan(zM) ? z.meanM : zM;
        return solarPosition(s, t, options);
    };

    SunField f;
    f.stepCells = stepCells;
    const SolarPosition centre = positionAt(0.5 * static_cast<double>(w), 0.5 * static_cast<double>(h), z.centreM);
    f.centreAzimuthDeg = centre.azimuthDeg;
    f.centreElevationDeg = centre.elevationDeg;
    const std::size_t ni = (w - 1) / stepCells + 2, nj = (h - 1) / stepCells + 2;
    f.azimuthDeg = Grid<float>(ni, nj);
    f.elevationDeg = Grid<float>(ni, nj);
    for (std::size_t j = 0; j < nj; ++j) {
        for (std::size_t i = 0; i < ni; ++i) {
            const double col = static_cast<double>(std::min(i * stepCells, w - 1)) + 0.5;
            const double row = static_cast<double>(std::min(j * stepCells, h - 1)) + 0.5;
            const SolarPosition p = positionAt(col, row, z.nodesM(i, j));
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

}  // namespace

SunField computeSunField(const Dem& dem, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells) {
    return sunFieldAtNodes(dem, dem.terrain.width(), dem.terrain.height(), nodeHeights(dem.terrain.heightsM, stepCells),
                           t, site, options, stepCells);
}

SunField computeSunField(const DemSource& source, UtcInstant t, const SolarSite& site,
                         const SpaOptions& options, std::size_t stepCells) {
    // Every window of a job asks for the same instant's field: made once per source.
    std::ostringstream key;
    key.precision(17);
    key << "sun field " << t.time_since_epoch().count() << " " << site.pressureHpa << " " << site.temperatureC << " "
        << site.latitudeDeg << " " << site.longitudeDeg << " " << site.elevationM << " "
        << options.deltaTSec.value_or(std::numeric_limits<double>::quiet_NaN()) << " " << options.sunRadiusDeg << " "
        << options.horizonRefractionDeg << " " << stepCells;
    const std::size_t nodes = ((source.width() - 1) / stepCells + 2) * ((source.height() - 1) / stepCells + 2);
    return *source.derived<SunField>(key.str(), 2 * nodes * sizeof(float), [&] {
        return sunFieldAtNodes(source.geometry(), source.width(), source.height(), source.nodeHeights(stepCells), t, site,
                               options, stepCells);
    });
}

}  // namespace demlight
