// demlight's sky bands side by side with SAGA's Sky View Factor (`saga_cmd ta_lighting 3`,
// SAGA 8.5) on one DEM crop: the accuracy of both against the dense reference of
// tests/sky_realdem_test.cpp, and the time of each. scripts/compare_saga.sh crops the DEM, runs
// and times both command-line tools, then runs this program, whose Markdown output becomes
// docs/compare/saga.md.
//
// Usage: demlight_sky_compare CROP.tif RUN_DIR MAX_DISTANCE_M [threads] [reference-cells]
//   RUN_DIR/times.tsv holds one line per timed run, "tool directions wall-seconds", with
//   tool "saga" (outputs RUN_DIR/saga_<N>_svf.tif and saga_<N>_visible.tif) or "demlight"
//   (RUN_DIR/demlight_<N>.tif, the four `demlight sky` bands). For every N in the file this
//   program also times demlight in-process with curvature off (see below).
//
// What SAGA computes (ta_lighting/view_shed.cpp, method "cell size"): for each of N grid
// azimuths i * 360 / N it steps one cell at a time from the cell centre, nearest cell, up to the
// search radius or the grid edge, and keeps phi_i = atan(max(0, max_k (z_q - z_p) / (k * cell))):
// a horizon clipped at 0, on a flat earth, with the rise of the k-th sample divided by its nominal
// distance k * cell size (not by the distance to the nearest cell it took). Then, with the cell's slope S and aspect A:
//   VISIBLE = 100 * mean_i (1 - phi_i / 90 deg)                 (percent, linear in the angle)
//   SVF     = mean_i [cos S cos^2 phi_i + sin S cos(az_i - A) ((pi/2 - phi_i) - sin phi_i cos phi_i)]
// (Haentzschel et al. 2005). SVF is the cosine-weighted view factor of the tilted cell, i.e.
// demlight's sky_K, except that (1) the horizon is clipped at 0, not at the tangent plane (sky
// below the horizontal that the cell sees is lost) and (2) nothing clamps the integral to the
// normal's hemisphere (where the tangent plane rises above the horizon, directions behind the
// cell enter with negative weight). VISIBLE is not demlight's sky_fraction (1 - mean sin h, the
// solid-angle fraction of the hemisphere) but its angular analogue.
//
// Reference (as tests/sky_realdem_test.cpp, but with curvature off because SAGA has none): in
// a fixed pseudo-random sample of valid cells at least the search distance from every crop edge
// (so neither tool's search meets an edge), ray-marched horizons (referenceHorizonAt) in 360
// azimuths (j + 0.5) degrees, integrated by referenceSky for svf_horizontal, sky_fraction and
// sky_K. SAGA's two outputs are also measured against their OWN definitions integrated over the
// same dense horizons (with the reference normal's slope and aspect), which separates SAGA's own
// errors from the difference in what it computes; those errors are split further by feeding
// SAGA's formulas with exact horizons at its N azimuths (sector sampling alone) and with horizons
// from a re-implementation of its search (checked against its output cell by cell).
//
// demlight in-process: exactly `demlight sky`'s computation (normals, sweepDirections,
// SkyAccumulator) with HorizonParams::curvature = false; the CLI cannot switch curvature off
// (the scene plan turns it on for this crop; with --refraction 0 its drop over the search
// distance is at most d / 2R = 0.017 deg at 3.75 km), so the CLI rows show the curvature-on
// result.
#include "bench/bench_timing.h"
#include "demlight/geo/dem.h"
#include "demlight/geo/raster.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using demlight::CellIndex;
using demlight::Grid;

/// Dense reference azimuths (1 degree apart, as tests/sky_realdem_test.cpp).
constexpr int kReferenceAzimuths = 360;
/// Default number of reference cells: enough for a stable 99th percentile.
constexpr std::size_t kDefaultReferenceCells = 1000;
/// Seed of the cell sample (fixed so that every run measures the same cells).
constexpr std::uint64_t kSampleSeed = 4242;
/// Albedo given to demlight's f_sky (not compared: SAGA has no such band).
constexpr double kAlbedo = 0.2;
/// SAGA writes VISIBLE as a percentage.
constexpr double kPercent = 100.0;

double since(std::chrono::steady_clock::time_point t0) { return demlight::bench::secondsSince(t0); }

/// Dense-reference values of one cell: demlight's three bands and SAGA's two definitions.
struct RefCell {
    CellIndex cell;
    double skyK = 0, svfHorizontal = 0, skyFraction = 0;  // referenceSky
    double sagaSvf = 0;      ///< Haentzschel's formula over the dense horizons, clipped at 0
    double sagaVisible = 0;  ///< 1 - mean max(h, 0) / 90 deg over the dense horizons
    bool horizonAbovePlane = false;  ///< every dense horizon >= 0 and >= the tangent plane
    double slopeRad = 0, aspectRad = 0;  ///< of the reference normal; aspect = true azimuth it leans to
    double gammaRad = 0;                 ///< meridian convergence: true azimuth of grid north
};

/// SAGA's SVF for one azimuth (true azimuth azRad, horizon phiRad >= 0) on a cell of slope
/// slopeRad facing aspectRad (the azimuth the normal leans toward, i.e. downslope); the mean over
/// azimuths is SAGA's SVF (Haentzschel et al. 2005; ta_lighting/view_shed.cpp Get_View_Shed).
double haentzschelTerm(double azRad, double phiRad, double slopeRad, double aspectRad) {
    const double s = std::sin(phiRad), c = std::cos(phiRad);
    return std::cos(slopeRad) * c * c +
           std::sin(slopeRad) * std::cos(azRad - aspectRad) * ((std::numbers::pi / 2 - phiRad) - s * c);
}

/// SAGA's two outputs (SVF; VISIBLE as a fraction) of one cell from N horizons phiRad[i] >= 0 at
/// the true azimuths i * 360 / N + azimuthOffsetRad.
std::pair<double, double> sagaFormulas(const std::vector<double>& phiRad, double azimuthOffsetRad,
                                       const RefCell& r) {
    double svf = 0, visible = 0;
    const auto n = static_cast<double>(phiRad.size());
    for (std::size_t i = 0; i < phiRad.size(); ++i) {
        const double azRad = static_cast<double>(i) * 2 * std::numbers::pi / n + azimuthOffsetRad;
        svf += haentzschelTerm(azRad, phiRad[i], r.slopeRad, r.aspectRad);
        visible += 1.0 - phiRad[i] / (std::numbers::pi / 2);
    }
    return {svf / n, visible / n};
}

/// SAGA's horizon search re-implemented from its description (ta_lighting/view_shed.cpp,
/// Get_Angle_Sectoral, method "cell size"), to check that the reading of SAGA above reproduces
/// its output: along grid azimuth i * 360 / N, unit steps (dx, dy) = (sin, cos) in cells with
/// SAGA's y axis pointing north; each step takes the NEAREST cell (rounding half up) and divides
/// its rise by the nominal distance k * cellSize, not by the distance to that cell; the search
/// stops at the grid edge or once the distance reaches radiusM. phi = atan(max(0, steepest)).
std::vector<double> sagaSteppingHorizonsRad(const Grid<float>& z, double cellSizeM, double radiusM,
                                            CellIndex c, std::size_t n) {
    const auto w = static_cast<long>(z.width()), h = static_cast<long>(z.height());
    const auto inGrid = [&](long x, long y) { return x >= 0 && y >= 0 && x < w && y < h; };
    const long y0 = h - 1 - static_cast<long>(c.row);  // SAGA's row index counts from the south
    const double z0 = z(c.col, c.row);
    std::vector<double> phi(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double az = static_cast<double>(i) * 2 * std::numbers::pi / static_cast<double>(n);
        const double dx = std::sin(az), dy = std::cos(az);
        double fx = static_cast<double>(c.col), fy = static_cast<double>(y0), distance = 0, steepest = 0;
        long x = static_cast<long>(c.col), y = y0;
        while (inGrid(x, y) && distance < radiusM) {
            fx += dx;
            fy += dy;
            x = static_cast<long>(0.5 + fx);
            y = static_cast<long>(0.5 + fy);
            distance += cellSizeM;
            if (inGrid(x, y)) {
                const double rise = (z(static_cast<std::size_t>(x), static_cast<std::size_t>(h - 1 - y)) - z0) / distance;
                steepest = std::max(steepest, rise);
            }
        }
        phi[i] = std::atan(steepest);
    }
    return phi;
}

std::vector<RefCell> reference(const demlight::Terrain& t, const demlight::Normals& normals,
                               const demlight::HorizonParams& p, std::size_t wanted, std::size_t* candidates) {
    // Valid cells farther than the search distance from every edge, all of them shuffled, then
    // the first `wanted`.
    std::vector<CellIndex> cells = demlight::sampleValidCells(t, static_cast<std::size_t>(-1), kSampleSeed, p.maxDistanceM);
    *candidates = cells.size();
    if (cells.size() > wanted) cells.resize(wanted);

    std::vector<std::vector<demlight::HorizonSample>> h(kReferenceAzimuths);
    demlight::HorizonParams rp = p;
    for (int j = 0; j < kReferenceAzimuths; ++j) {
        rp.azimuthDeg = (j + 0.5) * 360.0 / kReferenceAzimuths;
        h[static_cast<std::size_t>(j)] = demlight::referenceHorizonAt(t, rp, cells);
    }
    std::vector<RefCell> out;
    for (std::size_t i = 0; i < cells.size(); ++i) {
        bool truncated = false;
        for (const auto& az : h) truncated = truncated || az[i].truncated;
        if (truncated) continue;  // cannot happen with the margin above; kept as a guard
        const demlight::Enu n = normals.at(cells[i].col, cells[i].row);
        const auto horizon = [&](double azDeg) {
            const auto j = std::min(static_cast<std::size_t>(azDeg / (360.0 / kReferenceAzimuths)),
                                    static_cast<std::size_t>(kReferenceAzimuths - 1));
            return static_cast<double>(h[j][i].angleDeg);
        };
        const demlight::SkyReference sky = demlight::referenceSky(horizon, n, kReferenceAzimuths);
        RefCell r{cells[i], sky.skyK, sky.svfHorizontal, sky.skyFraction};
        const double slopeRad = std::acos(std::clamp(n.up, -1.0, 1.0));
        const double aspectRad = std::atan2(n.east, n.north);
        const double tanSlope = std::tan(slopeRad);
        double svf = 0, visible = 0;
        r.horizonAbovePlane = true;
        for (int j = 0; j < kReferenceAzimuths; ++j) {
            const double azRad = (j + 0.5) * 2 * std::numbers::pi / kReferenceAzimuths;
            const double hRad = h[static_cast<std::size_t>(j)][i].angleDeg * demlight::kDegToRad;
            const double phi = std::max(hRad, 0.0);
            // Tangent-plane elevation in this azimuth: the plane falls toward the aspect.
            const double planeRad = -std::atan(tanSlope * std::cos(azRad - aspectRad));
            r.horizonAbovePlane = r.horizonAbovePlane && hRad >= 0 && hRad >= planeRad;
            svf += haentzschelTerm(azRad, phi, slopeRad, aspectRad);
            visible += 1.0 - phi / (std::numbers::pi / 2);
        }
        r.slopeRad = slopeRad;
        r.aspectRad = aspectRad;
        r.gammaRad = t.convergence.at(static_cast<double>(cells[i].col), static_cast<double>(cells[i].row)) *
                     demlight::kDegToRad;
        r.sagaSvf = svf / kReferenceAzimuths;
        r.sagaVisible = visible / kReferenceAzimuths;
        out.push_back(r);
    }
    return out;
}

/// Error statistics of one band against its reference over the sample.
struct Stats {
    double mae = 0, p99 = 0, bias = 0;
};

Stats stats(const std::vector<double>& value, const std::vector<double>& ref) {
    std::vector<double> abs(value.size());
    Stats s;
    for (std::size_t i = 0; i < value.size(); ++i) {
        abs[i] = std::abs(value[i] - ref[i]);
        s.mae += abs[i];
        s.bias += value[i] - ref[i];
    }
    const auto n = static_cast<double>(value.size());
    s.mae /= n;
    s.bias /= n;
    std::sort(abs.begin(), abs.end());
    s.p99 = abs[static_cast<std::size_t>(std::ceil(0.99 * n)) - 1];
    return s;
}

std::string cell(const Stats& s) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.4f | %.4f | %+.4f", s.mae, s.p99, s.bias);
    return buf;
}

constexpr const char* kNoBand = "— | — | —";

/// Values of a grid at the sample cells; throws if the grid is not the crop's shape.
std::vector<double> atCells(const Grid<float>& g, const demlight::Terrain& t, const std::vector<RefCell>& ref,
                            const std::string& what, double scale = 1.0) {
    if (g.width() != t.width() || g.height() != t.height())
        throw demlight::Error(what + ": " + std::to_string(g.width()) + " x " + std::to_string(g.height()) +
                              " cells, expected the crop's " + std::to_string(t.width()) + " x " +
                              std::to_string(t.height()));
    std::vector<double> v;
    for (const RefCell& r : ref) {
        const double x = g(r.cell.col, r.cell.row);
        if (std::isnan(x)) throw demlight::Error(what + ": nodata at a reference cell");
        v.push_back(x * scale);
    }
    return v;
}

struct TimedRun {
    std::string tool;
    std::size_t directions = 0;
    double seconds = 0;
};

std::vector<TimedRun> readTimes(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw demlight::Error("cannot open " + path);
    std::vector<TimedRun> runs;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream s(line);
        TimedRun r;
        if (!(s >> r.tool >> r.directions >> r.seconds) || (r.tool != "saga" && r.tool != "demlight"))
            throw demlight::Error(path + ": expected 'saga|demlight N seconds', got '" + line + "'");
        runs.push_back(r);
    }
    return runs;
}

}  // namespace

int runCompare(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s CROP.tif RUN_DIR MAX_DISTANCE_M [threads] [reference-cells]\n", argv[0]);
        return 2;
    }
    try {
        const std::string cropPath = argv[1], runDir = argv[2];
        const double maxDistanceM = std::atof(argv[3]);
        const int threads = demlight::resolveThreadCount(argc > 4 ? std::atoi(argv[4]) : 0);
        const std::size_t wanted = argc > 5 ? static_cast<std::size_t>(std::atol(argv[5])) : kDefaultReferenceCells;
        const std::vector<TimedRun> runs = readTimes(runDir + "/times.tsv");

        const demlight::Dem dem = demlight::loadDem(cropPath);
        const demlight::Terrain& t = dem.terrain;
        const demlight::Normals normals = demlight::computeNormals(t);
        demlight::HorizonParams p;
        p.maxDistanceM = maxDistanceM;
        p.curvature = false;  // SAGA has no earth curvature

        // Dense reference.
        auto t0 = std::chrono::steady_clock::now();
        std::size_t candidates = 0;
        const std::vector<RefCell> ref = reference(t, normals, p, wanted, &candidates);
        const double refS = since(t0);
        if (ref.empty()) throw demlight::Error("no reference cell: the crop is too small for the search distance");
        std::vector<double> refK, refSvf, refFrac, refSagaSvf, refSagaVisible;
        double planeCheck = 0;
        std::size_t planeCells = 0;
        for (const RefCell& r : ref) {
            refK.push_back(r.skyK);
            refSvf.push_back(r.svfHorizontal);
            refFrac.push_back(r.skyFraction);
            refSagaSvf.push_back(r.sagaSvf);
            refSagaVisible.push_back(r.sagaVisible);
            // Where every horizon is >= 0 and above the tangent plane, SAGA's formula and K are
            // the same integral: a check of haentzschelTerm against referenceSky.
            if (r.horizonAbovePlane) {
                planeCheck = std::max(planeCheck, std::abs(r.sagaSvf - r.skyK));
                ++planeCells;
            }
        }

        std::printf("Crop: %zu x %zu cells of %.2f x %.2f m; search distance %.0f m; curvature off in the "
                    "reference and in-process demlight; %zu reference cells (a sample of the %zu valid cells "
                    "at least the search distance from every edge), %d reference azimuths, %.1f s; %d threads.\n\n",
                    t.width(), t.height(), t.cellWidthM[t.height() / 2], t.cellHeightM[t.height() / 2],
                    maxDistanceM, ref.size(), candidates, kReferenceAzimuths, refS, threads);

        // Rows of the main table, in the order of times.tsv, each followed by demlight in-process.
        std::printf("| tool (bands compared) | N | time (s) | K-like: MAE | p99 | bias | fraction-like: MAE | p99 | bias "
                    "| `svf_horizontal`: MAE | p99 | bias |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        std::map<std::size_t, std::pair<std::vector<double>, std::vector<double>>> sagaOut;  // N -> SVF, VISIBLE
        for (const TimedRun& run : runs) {
            const std::string n = std::to_string(run.directions);
            if (run.tool == "saga") {
                const std::string svfPath = runDir + "/saga_" + n + "_svf.tif";
                const std::string visPath = runDir + "/saga_" + n + "_visible.tif";
                const std::vector<double> svf = atCells(demlight::readRasterBand(svfPath).values, t, ref, svfPath);
                const std::vector<double> vis =
                    atCells(demlight::readRasterBand(visPath).values, t, ref, visPath, 1.0 / kPercent);
                std::printf("| SAGA `ta_lighting 3` (SVF; VISIBLE/100), wall | %zu | %.2f | %s | %s | %s |\n",
                            run.directions, run.seconds, cell(stats(svf, refK)).c_str(),
                            cell(stats(vis, refFrac)).c_str(), kNoBand);
                sagaOut[run.directions] = {svf, vis};
                continue;
            }
            const std::string path = runDir + "/demlight_" + n + ".tif";
            const std::vector<Grid<float>> bands = demlight::readRasterBands(path);
            if (bands.size() < 3) throw demlight::Error(path + ": expected the `demlight sky` bands");
            std::printf("| `demlight sky` CLI (sky_K; sky_fraction), wall, curvature on | %zu | %.2f | %s | %s | %s |\n",
                        run.directions, run.seconds, cell(stats(atCells(bands[2], t, ref, path), refK)).c_str(),
                        cell(stats(atCells(bands[1], t, ref, path), refFrac)).c_str(),
                        cell(stats(atCells(bands[0], t, ref, path), refSvf)).c_str());

            // The same computation in-process with curvature off (compute only, no I/O).
            t0 = std::chrono::steady_clock::now();
            const demlight::Normals nn = demlight::computeNormals(t);
            demlight::SkyAccumulator acc(nn.east, nn.north, nn.up, run.directions, {});
            demlight::sweepDirections(t, p, run.directions, [&](std::size_t i, const demlight::HorizonMap& m) {
                acc.addDirection(i, m.angleDeg);
            });
            const demlight::SkyMaps maps = acc.finish(kAlbedo);
            const double computeS = since(t0);
            std::printf("| demlight in-process (sky_K; sky_fraction), compute, curvature off | %zu | %.2f | %s | %s | %s |\n",
                        run.directions, computeS, cell(stats(atCells(maps.skyK, t, ref, "in-process"), refK)).c_str(),
                        cell(stats(atCells(maps.skyFraction, t, ref, "in-process"), refFrac)).c_str(),
                        cell(stats(atCells(maps.svfHorizontal, t, ref, "in-process"), refSvf)).c_str());
            std::fflush(stdout);
        }

        // SAGA's error against its own definitions, split into its sources: its formulas on exact
        // (reference) horizons at N azimuths = the sector sampling alone; on horizons found by its
        // nearest-cell stepping (re-implemented) = sampling + search; SAGA's own output.
        std::printf("\nSAGA against its own definitions integrated over the same dense reference horizons, "
                    "MAE (bias):\n\n");
        std::printf("| N | SVF: formula on exact horizons at N azimuths | SVF: on SAGA-style stepping horizons "
                    "| SVF: SAGA output | VISIBLE/100: exact horizons | VISIBLE/100: stepping | VISIBLE/100: SAGA output "
                    "| stepping − exact horizon (deg): mean, p99 of the absolute difference "
                    "| SAGA output vs re-implementation: SVF MAE / max, VISIBLE/100 MAE / max |\n");
        std::printf("|---|---|---|---|---|---|---|---|---|\n");
        const double cellSizeM = dem.band.ref.geoTransform[1];  // map units, as SAGA
        std::vector<CellIndex> refCells;
        for (const RefCell& r : ref) refCells.push_back(r.cell);
        const auto maeBias = [](const Stats& st) {
            char buf[48];
            std::snprintf(buf, sizeof buf, "%.4f (%+.4f)", st.mae, st.bias);
            return std::string(buf);
        };
        for (const auto& [n, out] : sagaOut) {
            std::vector<std::vector<double>> exactPhi(ref.size(), std::vector<double>(n));
            for (std::size_t j = 0; j < n; ++j) {
                demlight::HorizonParams rp = p;
                rp.azimuthDeg = demlight::directionAzimuthDeg(j, n);
                const std::vector<demlight::HorizonSample> hs = demlight::referenceHorizonAt(t, rp, refCells);
                for (std::size_t i = 0; i < ref.size(); ++i)
                    exactPhi[i][j] = std::max(0.0, hs[i].angleDeg * demlight::kDegToRad);
            }
            std::vector<double> exactSvf, exactVis, stepSvf, stepVis, stepDeg, exactDeg;
            for (std::size_t i = 0; i < ref.size(); ++i) {
                const std::vector<double> stepPhi =
                    sagaSteppingHorizonsRad(t.heightsM, cellSizeM, maxDistanceM, ref[i].cell, n);
                for (std::size_t j = 0; j < n; ++j) {
                    stepDeg.push_back(stepPhi[j] / demlight::kDegToRad);
                    exactDeg.push_back(exactPhi[i][j] / demlight::kDegToRad);
                }
                const auto [es, ev] = sagaFormulas(exactPhi[i], 0.0, ref[i]);
                const auto [ss, sv] = sagaFormulas(stepPhi, ref[i].gammaRad, ref[i]);
                exactSvf.push_back(es);
                exactVis.push_back(ev);
                stepSvf.push_back(ss);
                stepVis.push_back(sv);
            }
            double maxSvf = 0, maxVis = 0;
            for (std::size_t i = 0; i < ref.size(); ++i) {
                maxSvf = std::max(maxSvf, std::abs(out.first[i] - stepSvf[i]));
                maxVis = std::max(maxVis, std::abs(out.second[i] - stepVis[i]));
            }
            const Stats horizon = stats(stepDeg, exactDeg);
            std::printf("| %zu | %s | %s | %s | %s | %s | %s | %+.2f, %.2f | %.4f / %.4f, %.5f / %.5f |\n", n,
                        maeBias(stats(exactSvf, refSagaSvf)).c_str(), maeBias(stats(stepSvf, refSagaSvf)).c_str(),
                        maeBias(stats(out.first, refSagaSvf)).c_str(), maeBias(stats(exactVis, refSagaVisible)).c_str(),
                        maeBias(stats(stepVis, refSagaVisible)).c_str(),
                        maeBias(stats(out.second, refSagaVisible)).c_str(), horizon.bias, horizon.p99,
                        stats(out.first, stepSvf).mae, maxSvf,
                        stats(out.second, stepVis).mae, maxVis);
        }
        std::printf("\nDefinition gap, both sides dense (no sampling error): Häntzschel SVF vs sky_K %s; "
                    "1 − mean(h⁺/90°) vs sky_fraction %s (MAE | p99 | bias).\n",
                    cell(stats(refSagaSvf, refK)).c_str(), cell(stats(refSagaVisible, refFrac)).c_str());
        std::printf("\nCheck of the Häntzschel integration: on the %zu reference cells whose every dense horizon "
                    "is >= 0 and above the tangent plane it must equal sky_K; largest difference %.1e.\n",
                    planeCells, planeCheck);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}

int main(int argc, char** argv) {
    // The threads of the comparison's timed runs, entered once.
    return demlight::withThreads(argc > 4 ? std::atoi(argv[4]) : 0, [&] { return runCompare(argc, argv); });
}
