// The horizon's near field (HorizonParams::nearFieldSteps): time per cell and direction on one
// thread, and horizon error against the reference, for several near fields on one DEM. Runs of
// the near fields alternate (A B C A B C ...) and the median thread CPU time is reported, so a
// busy machine slows them alike; the ratios to the first near field are the figures to quote.
// Usage: demlight_near_field_bench DEM [--steps N ...] [--repeats R] [--cells C] [--max-distance M]
//                                  [--azimuths A ...]
//        (defaults: steps 0 and the scene plan's, 5 repeats, 1500 cells, the plan's distance,
//        azimuths 0 37 90 123.4;
//        a step count ending in c, e.g. 4c, forces the far field's grid-line crossings on, one
//        ending in n forces them off, a bare count takes the plan's choice)
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"
#include "demlight/core/error.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

using namespace demlight;

double threadSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
    std::string path;
    std::vector<int> steps;
    std::vector<char> crossingsOf;  // 'c' on, 'n' off, 0 the plan's
    int repeats = 5;
    std::size_t cells = 1500;
    double maxDistanceM = 0;
    std::vector<double> azimuths;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--steps" && i + 1 < argc) {
            while (i + 1 < argc && argv[i + 1][0] != '-') {
                const std::string v = argv[++i];
                steps.push_back(std::atoi(v.c_str()));
                crossingsOf.push_back(v.back() == 'c' || v.back() == 'n' ? v.back() : 0);
            }
        } else if (a == "--repeats" && i + 1 < argc) {
            repeats = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--cells" && i + 1 < argc) {
            cells = static_cast<std::size_t>(std::max(1, std::atoi(argv[++i])));
        } else if (a == "--azimuths" && i + 1 < argc) {
            while (i + 1 < argc && argv[i + 1][0] != '-') azimuths.push_back(std::atof(argv[++i]));
        } else if (a == "--max-distance" && i + 1 < argc) {
            maxDistanceM = std::atof(argv[++i]);
        } else {
            path = a;
        }
    }
    if (path.empty()) {
        std::fprintf(stderr,
                     "usage: %s DEM [--steps N ...] [--repeats R] [--cells C] [--max-distance M] [--azimuths A ...]\n",
                     argv[0]);
        return 2;
    }
    try {
        const Dem dem = loadDem(path);
        const Terrain& t = dem.terrain;
        QualityBudget budget;
        if (maxDistanceM > 0) budget.maxDistanceM = maxDistanceM;  // 0: the plan's
        const ScenePlan plan = planScene(t, Quality::Auto, budget);
        if (steps.empty()) {
            steps = {0, plan.nearFieldSteps};
            crossingsOf = {0, 0};
        }
        HorizonParams base = planHorizonParams(plan, budget.refraction);
        const std::vector<CellIndex> sample = sampleValidCells(t, cells, 20261202);
        std::printf("%s: %zu x %zu cells, search %.0f m, plan's near field %d steps\n", path.c_str(), t.width(),
                    t.height(), plan.maxDistanceM, plan.nearFieldSteps);
        std::printf("%8s %6s %12s %7s %10s %8s %8s\n", "azimuth", "steps", "ns/cell/dir", "ratio", "median", "p99",
                    ">5 deg");
        if (azimuths.empty()) azimuths = {0.0, 37.0, 90.0, 123.4};
        for (const double az : azimuths) {
            base.azimuthDeg = az;
            const std::vector<HorizonSample> ref = referenceHorizonAt(t, [&] {
                HorizonParams r = base;
                return r;
            }(), sample);
            std::vector<std::vector<double>> times(steps.size());
            std::vector<HorizonMap> maps(steps.size());
            std::vector<SweepBuffers> buffers(steps.size());
            for (int r = 0; r < repeats; ++r) {
                for (std::size_t k = 0; k < steps.size(); ++k) {
                    HorizonParams p = base;
                    p.nearFieldSteps = steps[k];
                    if (crossingsOf[k]) p.farFieldCrossings = crossingsOf[k] == 'c';
                    const double t0 = threadSeconds();
                    sweepHorizonInto(t, p, maps[k], buffers[k]);
                    times[k].push_back(threadSeconds() - t0);
                }
            }
            const double cellsD = static_cast<double>(t.width()) * static_cast<double>(t.height());
            const double first = percentile(times[0], 0.5);
            for (std::size_t k = 0; k < steps.size(); ++k) {
                std::vector<double> err;
                double big = 0;
                for (std::size_t i = 0; i < sample.size(); ++i) {
                    const double a = maps[k].angleDeg(sample[i].col, sample[i].row), b = ref[i].angleDeg;
                    if (!(a > kNoHorizonDeg) && !(b > kNoHorizonDeg)) continue;
                    err.push_back(std::abs(a - b));
                    big += std::abs(a - b) > 5.0;
                }
                const double s = percentile(times[k], 0.5);
                const std::string label = std::to_string(steps[k]) + (crossingsOf[k] ? std::string(1, crossingsOf[k]) : "");
                std::printf("%8.1f %6s %12.1f %7.2f %10.4f %8.3f %7.2f%%\n", az, label.c_str(), s / cellsD * 1e9, s / first,
                            percentile(err, 0.5), percentile(err, 0.99),
                            100.0 * big / static_cast<double>(std::max<std::size_t>(err.size(), 1)));
            }
        }
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
