// consumer DEM TIME: lights a DEM with the sun product of the installed demlight library and
// prints the share of its cells the sun reaches (docs/cpp.md). TIME: ISO 8601 with its offset.
#include <demlight/geo/dem_source.h>
#include <demlight/products/sun.h>
#include <demlight/core/error.h>

#include <cmath>
#include <iostream>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: consumer DEM TIME (e.g. 2024-06-21T07:30:00-07:00)\n";
        return 2;
    }
    try {
        const demlight::DemSource dem = demlight::DemSource::open(argv[1]);
        demlight::SunRequest request;
        request.time = demlight::parseZonedInstant(argv[2], "");
        const demlight::SunResult sun = demlight::sunProduct(dem, dem.whole(), request);

        const demlight::Grid<float>& visibility = sun.band("sun_visibility").values;
        std::size_t cells = 0, lit = 0;
        for (std::size_t i = 0; i < visibility.size(); ++i) {
            if (std::isnan(visibility.data()[i])) continue;  // DEM voids stay nodata
            ++cells;
            if (visibility.data()[i] > 0) ++lit;
        }
        std::cout << "sun azimuth " << sun.centreAzimuthDeg << " deg, elevation " << sun.centreElevationDeg
                  << " deg; " << lit << " of " << cells << " cells see the sun\n";
    } catch (const demlight::Error& e) {
        std::cerr << "consumer: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
