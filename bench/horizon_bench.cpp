// Horizon sweep cost in ns per cell per direction, on 1 thread and on all threads.
// Usage: demlight_horizon_bench DEM [runs] [max-distance-m]
//   (default: 5 runs, the scene's defaultMaxDistanceM).
#include "geo/dem.h"
#include "lighting/horizon.h"
#include "src/error.h"
#include "src/parallel.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

double medianSeconds(const demlight::Terrain& t, const demlight::HorizonParams& p, int runs) {
    std::vector<double> s;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        const demlight::HorizonMap m = demlight::sweepHorizon(t, p);
        s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(s.begin(), s.end());
    return s[s.size() / 2];
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
        p.maxDistanceM = argc > 3 ? std::atof(argv[3]) : demlight::defaultMaxDistanceM(t);
        const double cells = static_cast<double>(t.width() * t.height());
        const int all = demlight::resolveThreadCount(0);
        std::printf("%s: %zu x %zu cells, max distance %.0f m, median of %d runs\n", argv[1], t.width(),
                    t.height(), p.maxDistanceM, runs);
        std::printf("%10s %8s %16s %16s\n", "azimuth", "regions", "ns/cell 1 thr", "ns/cell all thr");
        for (double az : {0.0, 37.0, 90.0, 123.4, 225.0}) {
            p.azimuthDeg = az;
            p.threads = 1;
            const double one = medianSeconds(t, p, runs);
            p.threads = all;
            const double many = medianSeconds(t, p, runs);
            std::printf("%10.1f %8zu %16.1f %16.1f (%d threads)\n", az, demlight::sweepRegions(t, p).size(),
                        one / cells * 1e9, many / cells * 1e9, all);
        }
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
