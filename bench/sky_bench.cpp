// Sky and aperture cost by direction count on a whole DEM: sweep, sky accumulation and aperture
// accumulation, seconds and ns per cell per direction. The accuracy of each direction count is
// measured in tests/sky_realdem_test.cpp (README "Sky accuracy").
// Usage: demlight_sky_bench DEM [threads] [max-distance-m] [crop-width crop-height]
//   (default: all threads, the scene's defaultMaxDistanceM, the whole DEM; a crop is centred;
//   max-distance 0 = the scene default). tests/sky_realdem_test.cpp's crops and distances:
//   N44W072.hgt 2 6627 400 400; big_tujunga_srtm30m_utm11.tif 2 3750 600 500;
//   svalbard_longyearbyen_npi_dtm20.tif 2 2500 600 500.
#include "bench/bench_timing.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/aperture.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace {

double since(std::chrono::steady_clock::time_point t0) { return demlight::bench::secondsSince(t0); }

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEM [threads] [max-distance-m]\n", argv[0]);
        return 2;
    }
    try {
        const demlight::Dem dem = demlight::loadDem(argv[1]);
        const demlight::Terrain t = argc > 5 ? demlight::cropTerrainCentre(dem.terrain,
                                                                           static_cast<std::size_t>(std::atol(argv[4])),
                                                                           static_cast<std::size_t>(std::atol(argv[5])))
                                             : dem.terrain;
        const int threads = demlight::resolveThreadCount(argc > 2 ? std::atoi(argv[2]) : 0);
        demlight::HorizonParams p;
        p.maxDistanceM = argc > 3 && std::atof(argv[3]) > 0 ? std::atof(argv[3]) : demlight::defaultMaxDistanceM(t);
        const demlight::Normals normals = demlight::computeNormals(t);
        const double cells = static_cast<double>(t.width() * t.height());
        std::printf("%s: %zu x %zu cells, max distance %.0f m, %d threads\n", argv[1], t.width(), t.height(),
                    p.maxDistanceM, threads);
        std::printf("%4s %9s %9s %9s %9s %14s\n", "D", "sweep s", "sky s", "aper s", "total s", "ns/cell/dir");
        demlight::withThreads(threads, [&] {
        for (std::size_t d : {4u, 8u, 16u, 32u, 64u}) {
            demlight::SkyAccumulator sky(normals.east, normals.north, normals.up, d, {});
            demlight::ApertureAccumulator ap(normals.east, normals.north, normals.up, d);
            double skyS = 0, apS = 0;
            const auto t0 = std::chrono::steady_clock::now();
            demlight::sweepDirections(t, p, d, [&](std::size_t i, const demlight::HorizonMap& m) {
                auto t1 = std::chrono::steady_clock::now();
                sky.addDirection(i, m.angleDeg);
                skyS += since(t1);
                t1 = std::chrono::steady_clock::now();
                ap.addDirection(i, m.angleDeg);
                apS += since(t1);
            });
            auto t1 = std::chrono::steady_clock::now();
            [[maybe_unused]] const demlight::SkyMaps s = sky.finish(0.2);
            skyS += since(t1);
            t1 = std::chrono::steady_clock::now();
            [[maybe_unused]] const demlight::ApertureMaps a = ap.finish();
            apS += since(t1);
            const double total = since(t0);
            std::printf("%4zu %9.3f %9.3f %9.3f %9.3f %14.1f\n", d, total - skyS - apS, skyS, apS, total,
                        total / (cells * static_cast<double>(d)) * 1e9);
            std::fflush(stdout);
        }
        });
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
