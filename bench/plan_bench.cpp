// The scene plan's horizon sweep (--quality auto, one thread): time per cell and direction at
// four azimuths: the median and the minimum thread CPU time of R repeats (on a shared machine the
// minimum is the steadier figure: interference only adds time). It uses only calls the library has had
// since before the near field, so the same file built in a worktree of an earlier
// commit times that commit's sweep: run the two builds in alternation and quote the median of
// the per-round ratios (docs/journal.md, "Against the sweep before the near field").
// Usage: demlight_plan_bench [--whole] DEM [REPEATS [AZIMUTH]]   (default 9 repeats; one azimuth in
// degrees instead of the four, e.g. for a profiler; --whole: the plan's sweep over the whole DEM,
// without its range limit, as sky and aperture integrals run it)
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"

#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace {

double threadSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
    using namespace demlight;
    const bool whole = argc > 1 && std::string(argv[1]) == "--whole";
    if (whole) {
        --argc;
        ++argv;
    }
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s DEM [REPEATS]\n", argv[0]);
        return 2;
    }
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 9;
    std::vector<double> azimuths{0.0, 37.0, 90.0, 123.4};
    if (argc > 3) azimuths = {std::atof(argv[3])};
    try {
        const Dem dem = loadDem(argv[1]);
        const Terrain& t = dem.terrain;
        const QualityBudget budget;
        const ScenePlan plan = planScene(t, Quality::Auto, budget);
        HorizonParams p = planHorizonParams(plan, budget.refraction);
        if (whole) p.maxDistanceM = std::numeric_limits<double>::infinity();
        std::printf("search %.1f m", p.maxDistanceM);
        HorizonMap map;
        SweepBuffers buffers;
        const double cells = static_cast<double>(t.width()) * static_cast<double>(t.height());
        for (const double az : azimuths) {
            p.azimuthDeg = az;
            std::vector<double> s;
            for (int r = 0; r < repeats; ++r) {
                const double t0 = threadSeconds();
                sweepHorizonInto(t, p, map, buffers);
                s.push_back(threadSeconds() - t0);
            }
            std::sort(s.begin(), s.end());
            std::printf(" az %.1f %.2f min %.2f", az, s[s.size() / 2] / cells * 1e9, s.front() / cells * 1e9);
        }
        std::printf("\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
