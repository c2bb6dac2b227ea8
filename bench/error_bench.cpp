// The horizon error of both scene plans on whole DEMs, the statistic DEMLIGHT_EXPECTED_ERROR_DEG
// states (demlight/lighting/quality.h, ExpectedError): |error| against the full-physics reference (ray
// march, curvature on, whole DEM) over a fixed random sample of valid cells and six azimuths,
// where both meet terrain; auto's horizons clamped at the budget's lowest elevation (2 deg),
// full's on every horizon. The bench's auto-vs-full rows measure 600^2 crops; this measures
// whole tiles, where the search is longest and auto's scan tolerance the widest.
// Usage: demlight_error_bench [--cells N] [--csv PATH] DEM ...   (2 threads)
#include "bench/bench_timing.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/quality.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace demlight;

constexpr double kAzimuthsDeg[] = {0.0, 37.0, 90.0, 123.4, 200.0, 301.7};
constexpr std::uint64_t kSeed = 20240621;

struct Stats {
    double median = 0, p99 = 0;
};

Stats stats(std::vector<double> e) {
    Stats s;
    if (e.empty()) return s;
    std::sort(e.begin(), e.end());
    s.median = e[e.size() / 2];
    s.p99 = e[std::min(e.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(e.size())))];
    return s;
}

struct PlanResult {
    Stats error;
    double regionsPerAzimuth = 0, secondsPerAzimuth = 0;
};

PlanResult measure(const Terrain& t, const ScenePlan& plan, const std::vector<CellIndex>& cells,
                   const std::vector<double>& reference, double clampDeg) {
    HorizonParams p = planHorizonParams(plan, QualityBudget{}.refraction);
    std::vector<double> errors;
    PlanResult r;
    std::size_t k = 0;
    for (double az : kAzimuthsDeg) {
        p.azimuthDeg = az;
        r.regionsPerAzimuth += static_cast<double>(sweepRegions(t, p).size());
        HorizonMap m;
        r.secondsPerAzimuth += bench::medianSeconds(1, [&] { m = sweepHorizon(t, p); });
        for (const CellIndex& c : cells) {
            const double h = m.angleDeg(c.col, c.row), ref = reference[k++];
            if (h > kNoHorizonDeg && ref > kNoHorizonDeg)
                errors.push_back(std::abs(std::max(h, clampDeg) - std::max(ref, clampDeg)));
        }
    }
    const double n = static_cast<double>(std::size(kAzimuthsDeg));
    r.regionsPerAzimuth /= n;
    r.secondsPerAzimuth /= n;
    r.error = stats(std::move(errors));
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    std::size_t cellCount = 1000;
    std::string csvPath;
    std::vector<std::string> dems;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--cells" && i + 1 < argc) {
            cellCount = static_cast<std::size_t>(std::max(1, std::atoi(argv[++i])));
        } else if (a == "--csv" && i + 1 < argc) {
            csvPath = argv[++i];
        } else {
            dems.push_back(a);
        }
    }
    if (dems.empty()) {
        std::fprintf(stderr, "usage: %s [--cells N] [--csv PATH] DEM ...\n", argv[0]);
        return 2;
    }
    std::FILE* csv = csvPath.empty() ? nullptr : std::fopen(csvPath.c_str(), "w");
    if (csv)
        std::fprintf(csv, "dem,width,height,plan,scope,median_deg,p99_deg,regions_per_azimuth,ms_per_azimuth\n");
    try {
        std::printf("%-34s %-5s %-22s %9s %8s %8s %8s\n", "DEM", "plan", "scope", "median", "p99", "regions",
                    "ms/az");
        for (const std::string& path : dems) {
            const Dem dem = loadDem(path);
            const Terrain& t = dem.terrain;
            const std::vector<CellIndex> cells = sampleValidCells(t, cellCount, kSeed);
            HorizonParams ref;  // full physics: curvature on, the whole DEM
            std::vector<double> reference;
            for (double az : kAzimuthsDeg) {
                ref.azimuthDeg = az;
                for (const HorizonSample& s : referenceHorizonAt(t, ref, cells)) reference.push_back(s.angleDeg);
            }
            const QualityBudget budget;
            const std::string name = std::filesystem::path(path).stem().string();
            for (const Quality q : {Quality::Auto, Quality::Full}) {
                const ScenePlan plan = planScene(t, q, budget);
                const double clamp = q == Quality::Auto ? budget.lowestElevationDeg : -90.0;
                const PlanResult r = measure(t, plan, cells, reference, clamp);
                const std::string scope = q == Quality::Auto ? "horizons >= 2 deg" : "every horizon";
                std::printf("%-34s %-5s %-22s %9.4f %8.3f %8.1f %8.1f\n", name.c_str(),
                            std::string(qualityName(q)).c_str(), scope.c_str(), r.error.median, r.error.p99,
                            r.regionsPerAzimuth, r.secondsPerAzimuth * 1e3);
                if (csv)
                    std::fprintf(csv, "%s,%zu,%zu,%s,%s,%.5f,%.4f,%.2f,%.2f\n", name.c_str(), t.width(), t.height(),
                                 std::string(qualityName(q)).c_str(), scope.c_str(), r.error.median, r.error.p99,
                                 r.regionsPerAzimuth, r.secondsPerAzimuth * 1e3);
            }
            std::fflush(stdout);
        }
    } catch (const demlight::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    if (csv) std::fclose(csv);
    return 0;
}
