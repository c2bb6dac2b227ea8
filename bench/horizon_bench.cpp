// Horizon sweep cost in ns per cell per direction, on 1 thread and on all threads.
// Usage: demlight_horizon_bench DEM [runs] [max-distance-m] [azimuths-deg]
//   (default: 5 runs, the scene's defaultMaxDistanceM (0 = default too), azimuths
//   0,37,90,123.4,225; azimuths as a comma-separated list). Each azimuth is timed on 1 thread
//   and on all threads within the same run, so their ratio is not skewed by load drift.
#include "bench/bench_timing.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

double medianSeconds(const demlight::Terrain& t, const demlight::HorizonParams& p, int runs) {
    return demlight::bench::medianSeconds(runs, [&] { const demlight::HorizonMap m = demlight::sweepHorizon(t, p); });
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEM [runs] [max-distance-m]\n", argv[0]);
        return 2;
    }
    try {
        const demlight::Dem dem = demlight::loadDem(argv[1]);
        const demlight::Terrain& t = dem.terrain;
        const int runs = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
        demlight::HorizonParams p;
        const double maxDistanceM = argc > 3 ? std::atof(argv[3]) : 0.0;
        p.maxDistanceM = maxDistanceM > 0.0 ? maxDistanceM : demlight::defaultMaxDistanceM(t);
        std::vector<double> azimuths{0.0, 37.0, 90.0, 123.4, 225.0};
        if (argc > 4) {
            azimuths.clear();
            std::stringstream list(argv[4]);
            for (std::string item; std::getline(list, item, ',');) azimuths.push_back(std::atof(item.c_str()));
        }
        const double cells = static_cast<double>(t.width() * t.height());
        const int all = demlight::resolveThreadCount(0);
        std::printf("%s: %zu x %zu cells, max distance %.0f m, median of %d runs\n", argv[1], t.width(),
                    t.height(), p.maxDistanceM, runs);
        std::printf("%10s %8s %16s %16s %8s\n", "azimuth", "regions", "ns/cell 1 thr", "ns/cell all thr", "ratio");
        for (double az : azimuths) {
            p.azimuthDeg = az;
            const double one = demlight::withThreads(1, [&] { return medianSeconds(t, p, runs); });
            const double many = demlight::withThreads(all, [&] { return medianSeconds(t, p, runs); });
            std::printf("%10.1f %8zu %16.1f %16.1f %8.2f (%d threads)\n", az, demlight::sweepRegions(t, p).size(),
                        one / cells * 1e9, many / cells * 1e9, one / many, all);
        }
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
