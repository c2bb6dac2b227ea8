// Speed against accuracy (docs/design.md §7): every method and parameter set on the same
// DEM and the same random sample of non-truncated cells, in one run. For each: time per cell
// (whole-grid run time / cells, median of repeats, one thread) and error against the reference.
//
// Usage: demlight_tradeoff_bench [--dem PATH ...] [--out DIR] [--quick]
//   Writes DIR/tradeoff.csv (method, params, dem, ns_per_cell, error_metric, error_value, pareto,
//   notes); scripts/bench.sh draws the chart from it with bench/tradeoff_chart.gnuplot.
//   The rows "quality auto" and "quality full" are the scene plans of --quality (demlight/lighting/
//   quality.h) on the crop: what `demlight sun` and `demlight sky` run by default and with full.
// Usage: demlight_tradeoff_bench --auto-vs-full [--dem PATH ...] [--out DIR] [--quick]
//   Whole DEMs (default: the bundled samples): wall time and error of --quality auto against
//   full for horizon, sun and sky; writes DIR/auto_vs_full.csv and prints a markdown table.
//
// References (docs/design.md §7), full physics: the ray march (referenceHorizonAt, curvature on,
// refraction 0.13) over the whole crop, i.e. everything the DEM knows; the same reference as
// DEMLIGHT_EXPECTED_ERROR_DEG and tests/quality_realdem_test.cpp.
//  - Sun horizon: the reference at the sun azimuth.
//  - Sun visibility / irradiance: the horizon method (Hoffman & Mitchell 2001b, Eq. 3, 5-7) on
//    the reference horizons with the exact normals.
//  - Sky K: the dense reference (the reference in M azimuths, integrated by referenceSky), as in
//    tests/sky_realdem_test.cpp.
// D0 is the scene's default search distance on the crop (defaultMaxDistanceM: relief / tan 2 deg
// capped by the crop's diagonal); the rows that vary the distance are fractions of it.
// Cells: a fixed pseudo-random sample of valid cells at least 2 M from every crop edge, M = D0
// capped at a sixth of the crop's shorter side, so that every cell has terrain around it (the
// whole-crop reference is cut by the crop edge beyond that, as every method is).
#include "bench/bench_timing.h"
#include "demlight/core/parallel.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/aperture.h"
#include "demlight/lighting/directions.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/lighting_models.h"
#include "demlight/lighting/quality.h"
#include "demlight/lighting/sky.h"
#include "demlight/lighting/sun.h"
#include "demlight/lighting/sun_frame.h"
#include "demlight/lighting/sunhours.h"
#include "demlight/lighting/surface.h"
#include "demlight/core/error.h"
#include "demlight/core/sun_field.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace demlight {
namespace {

/// The off-grid sun of the sun rows: azimuth between sweep directions for every N tested.
constexpr double kSunAzimuthDeg = 123.4;
/// A low sun, so that shadows are long and horizons matter.
constexpr double kSunElevationDeg = 5.0;
/// The sampling margin M is D0 capped at this fraction of the crop's shorter side, so that a
/// sample of cells 2 M from every edge remains.
constexpr double kMarginSideFraction = 1.0 / 6.0;
/// Timed runs use one thread: the figure is cost per core, comparable with GRASS r.horizon.
constexpr int kThreads = 1;
/// Palette normals: the table size of Hoffman & Mitchell 2001a.
constexpr std::size_t kPaletteSize = 256;
/// Palette training: Lloyd iterations on at most this many normals.
constexpr int kPaletteIterations = 10;
constexpr std::size_t kPaletteTrainingCells = 50000;
/// Hoffman & Mitchell 2001a: 0x0000 = 0 deg and 0xFFFF = 90 deg.
constexpr double kFixedFullScaleDeg = 90.0;
constexpr double kFixedMax = 65535.0;
/// Directions of the 16-bit sky rows (the default of `demlight sky`).
constexpr std::size_t kFixedSkyDirections = 32;
/// Fixed sample seed (the same cells every run).
constexpr std::uint64_t kSampleSeed = 4242;

struct Options {
    std::vector<std::string> dems;
    std::string outDir = "docs/bench";
    bool quick = false;
    bool autoVsFull = false;           ///< the auto-vs-full table on whole DEMs instead
    std::size_t cropCells = 400;       ///< centred crop, cells a side
    std::size_t sampleCells = 1000;    ///< reference cells before truncation filtering
    int referenceAzimuths = 360;       ///< dense sky reference
    int repeats = 3;
};

struct Row {
    std::string method, params, dem;
    double nsPerCell = 0;
    std::string metric;
    double error = 0;
    std::string notes;
    bool pareto = false;
};

using bench::medianSeconds;
double seconds(std::chrono::steady_clock::time_point t0) { return bench::secondsSince(t0); }

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / static_cast<double>(v.size());
}

std::string fmt(const char* f, double a) {
    char b[64];
    std::snprintf(b, sizeof b, f, a);
    return b;
}

/// 16-bit fixed-point horizon storage. Hoffman & Mitchell 2001a map 0 deg -> 0x0000 and 90 deg ->
/// 0xFFFF (only the quarter circle: negative horizons are stored as 0); the signed variant spends
/// the same 16 bits on [-90, 90] deg (step 0.0027 deg) so downhill horizons survive.
enum class FixedRange { Seed0To90, Signed };

std::uint16_t toFixed16(float deg, FixedRange range) {
    const double lo = range == FixedRange::Seed0To90 ? 0.0 : -kFixedFullScaleDeg;
    const double x = (std::clamp(static_cast<double>(deg), lo, kFixedFullScaleDeg) - lo) / (kFixedFullScaleDeg - lo);
    return static_cast<std::uint16_t>(std::lround(x * kFixedMax));
}
float fromFixed16(std::uint16_t v, FixedRange range) {
    const double lo = range == FixedRange::Seed0To90 ? 0.0 : -kFixedFullScaleDeg;
    return static_cast<float>(lo + v / kFixedMax * (kFixedFullScaleDeg - lo));
}

/// Quantises a horizon grid through 16-bit storage and back (NaN = nodata is kept out of band).
Grid<float> fixed16RoundTrip(const Grid<float>& deg, FixedRange range) {
    std::vector<std::uint16_t> stored(deg.size());
    for (std::size_t i = 0; i < deg.size(); ++i) stored[i] = std::isnan(deg.data()[i]) ? 0 : toFixed16(deg.data()[i], range);
    Grid<float> out(deg.width(), deg.height());
    for (std::size_t i = 0; i < deg.size(); ++i)
        out.data()[i] = std::isnan(deg.data()[i]) ? deg.data()[i] : fromFixed16(stored[i], range);
    return out;
}

/// 256 unit normals on the upper hemisphere, evenly spread (Fibonacci lattice in up in [0, 1]).
std::vector<Enu> fibonacciHemisphere(std::size_t n) {
    std::vector<Enu> out;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (std::size_t i = 0; i < n; ++i) {
        const double up = 1.0 - (static_cast<double>(i) + 0.5) / static_cast<double>(n);
        const double r = std::sqrt(std::max(0.0, 1.0 - up * up));
        const double a = golden * static_cast<double>(i);
        out.push_back({r * std::cos(a), r * std::sin(a), up});
    }
    return out;
}

std::size_t nearestPaletteEntry(const std::vector<Enu>& table, double e, double n, double u) {
    std::size_t best = 0;
    double bestDot = -2;
    for (std::size_t k = 0; k < table.size(); ++k) {
        const double d = table[k].east * e + table[k].north * n + table[k].up * u;
        if (d > bestDot) bestDot = d, best = k;
    }
    return best;
}

/// Palette normals (Hoffman & Mitchell 2001a, "palette normal mapping"): the table and one index
/// per cell (255 at nodata is harmless: nodata cells are never read).
struct Palette {
    std::vector<Enu> table;
    std::vector<std::uint8_t> index;
};

/// Lloyd iterations (k-means on the sphere, means renormalised) starting from `table`, trained on
/// a fixed subsample; then every cell gets its nearest entry.
Palette buildPalette(const Normals& normals, std::vector<Enu> table, int iterations) {
    const std::size_t cells = normals.up.size();
    std::vector<std::size_t> valid;
    for (std::size_t i = 0; i < cells; ++i)
        if (!std::isnan(normals.up.data()[i])) valid.push_back(i);
    std::mt19937_64 rng(kSampleSeed);
    std::shuffle(valid.begin(), valid.end(), rng);
    if (valid.size() > kPaletteTrainingCells) valid.resize(kPaletteTrainingCells);
    for (int it = 0; it < iterations; ++it) {
        std::vector<std::array<double, 3>> sum(table.size(), {0, 0, 0});
        for (std::size_t i : valid) {
            const double e = normals.east.data()[i], n = normals.north.data()[i], u = normals.up.data()[i];
            auto& s = sum[nearestPaletteEntry(table, e, n, u)];
            s[0] += e, s[1] += n, s[2] += u;
        }
        for (std::size_t k = 0; k < table.size(); ++k) {
            const double len = std::hypot(sum[k][0], sum[k][1], sum[k][2]);
            if (len > 0) table[k] = {sum[k][0] / len, sum[k][1] / len, sum[k][2] / len};  // empty: keep
        }
    }
    Palette p{table, std::vector<std::uint8_t>(cells, 0)};
    for (std::size_t i = 0; i < cells; ++i)
        if (!std::isnan(normals.up.data()[i]))
            p.index[i] = static_cast<std::uint8_t>(
                nearestPaletteEntry(table, normals.east.data()[i], normals.north.data()[i], normals.up.data()[i]));
    return p;
}

/// One frame of palette shading (Hoffman & Mitchell 2001a): the 256-entry lighting table
/// max(0, N_k . s) and the per-entry tangent-plane elevation, then per cell a lookup times the
/// disk visibility.
Grid<float> paletteIrradiance(const Palette& pal, const Grid<float>& horizonDeg) {
    const Enu s = directionEnu(kSunAzimuthDeg, kSunElevationDeg);
    std::array<float, kPaletteSize> lambert{}, planeDeg{};
    for (std::size_t k = 0; k < pal.table.size(); ++k) {
        const Enu& n = pal.table[k];
        lambert[k] = static_cast<float>(std::max(0.0, n.east * s.east + n.north * s.north + n.up * s.up));
        planeDeg[k] = static_cast<float>(tangentPlaneElevationDeg(n, kSunAzimuthDeg));
    }
    Grid<float> out(horizonDeg.width(), horizonDeg.height());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const float h = horizonDeg.data()[i];
        const std::uint8_t k = pal.index[i];
        out.data()[i] = std::isnan(h) ? h
                                      : static_cast<float>(lambert[k] * sunVisibility(std::max(h, planeDeg[k]),
                                                                                      kSunElevationDeg, kSunDiameterDeg));
    }
    return out;
}

/// Linear interpolation in azimuth between the two stack directions bracketing azimuthDeg (the
/// same rule as sunLightFromStack).
float stackHorizonAt(const HorizonStack& stack, std::size_t col, std::size_t row, double azimuthDeg) {
    const std::size_t n = stack.angleDeg.size();
    const double x = azimuthDeg / (360.0 / static_cast<double>(n));
    const auto i0 = static_cast<std::size_t>(std::floor(x)) % n;
    const double w = x - std::floor(x);
    return static_cast<float>((1 - w) * stack.angleDeg[i0](col, row) + w * stack.angleDeg[(i0 + 1) % n](col, row));
}

class DemBench {
public:
    DemBench(const Options& o, const std::string& path, std::vector<Row>& rows) : o_(o), rows_(rows) {
        name_ = std::filesystem::path(path).stem().string();
        const Dem dem = loadDem(path);
        t_ = cropTerrainCentre(dem.terrain, o.cropCells, o.cropCells);
        const std::size_t w = t_.width(), h = t_.height();
        cells_ = static_cast<double>(w * h);
        normals_ = computeNormals(t_);
        const std::size_t mid = t_.height() / 2;
        const double sideM = std::min(t_.cellWidthM[mid] * static_cast<double>(w), t_.cellHeightM[mid] * static_cast<double>(h));
        d0_ = defaultMaxDistanceM(t_);
        marginM_ = std::min(d0_, kMarginSideFraction * sideM);
        base_.azimuthDeg = kSunAzimuthDeg;
        base_.maxDistanceM = d0_;
        std::printf("%s: crop %zu x %zu cells (%.0f x %.0f m cells), D0 = %.0f m, sample margin %.0f m\n", name_.c_str(), w, h,
                    t_.cellWidthM[mid], t_.cellHeightM[mid], d0_, 2 * marginM_);
    }

    void run() {
        sampleAndReference();
        sunRows();
        skyRows();
        std::fflush(stdout);
    }

private:
    void add(std::string method, std::string params, double seconds, std::string metric, double error,
             std::string notes = {}) {
        const double ns = seconds / cells_ * 1e9;
        std::printf("  %-22s %-16s %10.1f ns/cell  %-26s %.3g  %s\n", method.c_str(), params.c_str(), ns, metric.c_str(), error,
                    notes.c_str());
        rows_.push_back({std::move(method), std::move(params), name_, ns, std::move(metric), error, std::move(notes), false});
    }

    /// Sample cells; compute the sun and sky references (full physics, the whole crop).
    void sampleAndReference() {
        std::vector<CellIndex> cand = sampleValidCells(t_, o_.sampleCells, kSampleSeed, 2 * marginM_);
        if (cand.empty()) throw Error(name_ + ": no cells 2 M from the crop edge; use a larger crop");

        // Sun truth over the whole crop, and the reference limited to D0 (timed: one azimuth per
        // cell).
        HorizonParams p = base_;
        p.maxDistanceM = std::numeric_limits<double>::infinity();
        auto t0 = std::chrono::steady_clock::now();
        const auto truth = referenceHorizonAt(t_, p, cand);
        refTruthS_ = seconds(t0) / static_cast<double>(cand.size()) * cells_;
        t0 = std::chrono::steady_clock::now();
        const auto atD0 = referenceHorizonAt(t_, base_, cand);
        refD0S_ = seconds(t0) / static_cast<double>(cand.size()) * cells_;

        // Dense sky reference over the whole crop.
        const int m = o_.referenceAzimuths;
        std::vector<std::vector<HorizonSample>> sky(static_cast<std::size_t>(m));
        t0 = std::chrono::steady_clock::now();
        HorizonParams sp = base_;
        sp.maxDistanceM = std::numeric_limits<double>::infinity();
        for (int j = 0; j < m; ++j) {
            sp.azimuthDeg = (j + 0.5) * 360.0 / m;
            sky[static_cast<std::size_t>(j)] = referenceHorizonAt(t_, sp, cand);
        }
        const double skyHorizonS = seconds(t0);

        t0 = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < cand.size(); ++i) {
            const CellIndex c = cand[i];
            const Enu n = normals_.at(c.col, c.row);
            sample_.push_back(c);
            truthH_.push_back(truth[i].angleDeg);
            refD0H_.push_back(atD0[i].angleDeg);
            truthVis_.push_back(sunVisibilityClamped(n, truth[i].angleDeg, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg));
            truthIrr_.push_back(sunIrradiance(n, truth[i].angleDeg, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg));
            const auto horizon = [&](double azDeg) {
                const auto j = std::min(static_cast<std::size_t>(azDeg / (360.0 / m)), static_cast<std::size_t>(m - 1));
                return static_cast<double>(sky[j][i].angleDeg);
            };
            refK_.push_back(referenceSky(horizon, n, m).skyK);
        }
        refSkyS_ = (skyHorizonS + seconds(t0)) / static_cast<double>(cand.size()) * cells_;
        std::printf("  %zu sampled cells; sky reference %d azimuths\n", sample_.size(), m);
    }

    std::vector<float> sampleOf(const Grid<float>& g) const {
        std::vector<float> v;
        for (const CellIndex& c : sample_) v.push_back(g(c.col, c.row));
        return v;
    }

    double horizonMedianError(const std::vector<float>& h) const {
        std::vector<double> e;
        for (std::size_t i = 0; i < h.size(); ++i) e.push_back(std::abs(static_cast<double>(h[i]) - truthH_[i]));
        return median(e);
    }
    double maeAgainst(const std::vector<float>& v, const std::vector<double>& ref) const {
        std::vector<double> e;
        for (std::size_t i = 0; i < v.size(); ++i) e.push_back(std::abs(static_cast<double>(v[i]) - ref[i]));
        return mean(e);
    }
    std::vector<float> visibilityFromHorizons(const std::vector<float>& h) const {
        std::vector<float> v;
        for (std::size_t i = 0; i < h.size(); ++i)
            v.push_back(static_cast<float>(sunVisibilityClamped(normals_.at(sample_[i].col, sample_[i].row), h[i], kSunAzimuthDeg,
                                                                kSunElevationDeg, kSunDiameterDeg)));
        return v;
    }

    /// Horizon and visibility rows of a sun method whose horizons at the sample are `h`.
    void sunPair(const std::string& method, const std::string& params, double s, const std::vector<float>& h,
                 const std::vector<float>& vis, const std::string& notes = {}) {
        add(method, params, s, "horizon_median_abs_deg", horizonMedianError(h), notes);
        add(method, params, s, "sun_visibility_mae", maeAgainst(vis, truthVis_), notes);
    }

    void sunRows() {
        const SunField field = SunField::uniform(kSunAzimuthDeg, kSunElevationDeg);
        const std::string floorNote = "reference itself: error 0 by definition; plotted at the chart floor";
        add("reference", "whole crop", refTruthS_, "horizon_median_abs_deg", 0, floorNote + "; ray march timed on the sample");
        add("reference", "whole crop", refTruthS_, "sun_visibility_mae", 0, floorNote);
        add("reference", "whole crop", refTruthS_, "sun_irradiance_mae", 0, floorNote);
        sunPair("reference", "D0", refD0S_, refD0H_, visibilityFromHorizons(refD0H_), "ray march at the default distance");
        qualitySunRows(field);

        // Exact per-instant sweep at the sun azimuth, and its irradiance.
        HorizonMap exact;
        SunLight exactLight;
        const double exactS = medianSeconds(o_.repeats, [&] {
            exact = sweepHorizon(t_, base_);
            exactLight = computeSunLight(t_, exact, normals_, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg);
        });
        const double shadeS = medianSeconds(o_.repeats, [&] {
            exactLight = computeSunLight(t_, exact, normals_, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg);
        });
        const std::vector<float> exactH = sampleOf(exact.angleDeg);
        sunPair("exact sweep", "D0", exactS, exactH, sampleOf(exactLight.visibility));
        add("exact sweep", "D0 float normals", exactS, "sun_irradiance_mae", maeAgainst(sampleOf(exactLight.irradiance), truthIrr_),
            "shading pass alone " + fmt("%.1f", shadeS / cells_ * 1e9) + " ns/cell; normals 12 B/cell");

        // Azimuth interpolation between N precomputed directions.
        for (std::size_t n : {4u, 8u, 16u, 32u, 64u}) {
            HorizonStack stack;
            const double stackS = medianSeconds(o_.repeats, [&] { stack = computeHorizonStack(t_, n, base_); });
            SunLight light;
            const double interpS = medianSeconds(o_.repeats, [&] {
                light = sunLightFromStack(t_, normals_, stack, field, kSunDiameterDeg);
            });
            std::vector<float> h;
            for (const CellIndex& c : sample_) h.push_back(stackHorizonAt(stack, c.col, c.row, kSunAzimuthDeg));
            sunPair("interpolated", "N=" + std::to_string(n), stackS + interpS, h, sampleOf(light.visibility),
                    "time = N sweeps + one interpolated frame; per extra instant " + fmt("%.1f", interpS / cells_ * 1e9) +
                        " ns/cell");
        }

        // Maximum search distance.
        for (double f : {0.1, 0.25, 0.5}) {
            HorizonParams p = base_;
            p.maxDistanceM = f * d0_;
            HorizonMap m;
            SunLight l;
            const double s = medianSeconds(o_.repeats, [&] {
                m = sweepHorizon(t_, p);
                l = computeSunLight(t_, m, normals_, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg);
            });
            sunPair("exact sweep distance", fmt("%gxD0", f), s, sampleOf(m.angleDeg), sampleOf(l.visibility),
                    fmt("max distance %.0f m", p.maxDistanceM));
        }

        // Curvature off (flat earth) against the curved reference.
        {
            HorizonParams p = base_;
            p.curvature = false;
            HorizonMap m;
            SunLight l;
            const double s = medianSeconds(o_.repeats, [&] {
                m = sweepHorizon(t_, p);
                l = computeSunLight(t_, m, normals_, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg);
            });
            sunPair("exact sweep flat earth", "D0 curvature off", s, sampleOf(m.angleDeg), sampleOf(l.visibility),
                    "no curvature or refraction; reference is curved");
        }

        // 16-bit fixed-point horizon storage (Hoffman & Mitchell 2001a), the paper's range and a
        // signed range.
        for (const FixedRange range : {FixedRange::Seed0To90, FixedRange::Signed}) {
            const bool seed = range == FixedRange::Seed0To90;
            HorizonMap m;
            Grid<float> q;
            SunLight l;
            const double s = medianSeconds(o_.repeats, [&] {
                m = sweepHorizon(t_, base_);
                q = fixed16RoundTrip(m.angleDeg, range);
                m.angleDeg = q;
                l = computeSunLight(t_, m, normals_, kSunAzimuthDeg, kSunElevationDeg, kSunDiameterDeg);
            });
            const std::vector<float> h = sampleOf(q);
            std::vector<double> added;
            for (std::size_t i = 0; i < h.size(); ++i)
                if (!seed || exactH[i] >= 0) added.push_back(std::abs(static_cast<double>(h[i]) - exactH[i]));
            const double maxAdded = added.empty() ? 0 : *std::max_element(added.begin(), added.end());
            sunPair("fixed16 sweep", seed ? "D0 unsigned 0..90" : "D0 signed -90..90", s, h, sampleOf(l.visibility),
                    "2 B/cell/direction instead of 4 (50% saved); added error vs float sweep max " + fmt("%.4f", maxAdded) + " deg" +
                        (seed ? " on h>=0; negative horizons stored as 0" : ""));
        }

        // Palette normals (Hoffman & Mitchell 2001a): 256-entry normal table, per frame one
        // lighting table.
        for (const bool trained : {false, true}) {
            const auto t0 = std::chrono::steady_clock::now();
            const Palette pal = buildPalette(normals_, fibonacciHemisphere(kPaletteSize), trained ? kPaletteIterations : 0);
            const double buildS = seconds(t0);
            Grid<float> irr;
            const double frameS = medianSeconds(o_.repeats, [&] { irr = paletteIrradiance(pal, exact.angleDeg); });
            std::vector<double> angle;
            for (const CellIndex& c : sample_) {
                const Enu n = normals_.at(c.col, c.row);
                const Enu& k = pal.table[pal.index[c.row * t_.width() + c.col]];
                angle.push_back(std::acos(std::clamp(n.east * k.east + n.north * k.north + n.up * k.up, -1.0, 1.0)) * 180 /
                                std::numbers::pi);
            }
            add("palette normals", trained ? "256 k-means" : "256 fibonacci", exactS - shadeS + frameS, "sun_irradiance_mae",
                maeAgainst(sampleOf(irr), truthIrr_),
                "exact sweep + palette shading pass " + fmt("%.1f", frameS / cells_ * 1e9) + " ns/cell; 1 B/cell; median normal error " +
                    fmt("%.2f", median(angle)) + " deg; table built in " + fmt("%.2f", buildS) + " s (not timed)");
        }

        // Aperture model, exact and smoothstep (sun visibility against the horizon method): the
        // covered fraction of the sun cap, A_int(sun cap, aperture cap) / A_sun (Oat & Sander).
        const Enu s = directionEnu(kSunAzimuthDeg, kSunElevationDeg);
        const double sunRadiusRad = kSunDiameterDeg / 2 * std::numbers::pi / 180;
        for (std::size_t n : {8u, 32u}) {
            for (const bool smooth : {false, true}) {
                Grid<float> vis;
                const double sec = medianSeconds(o_.repeats, [&] {
                    ApertureAccumulator acc(normals_.east, normals_.north, normals_.up, n);
                    sweepDirections(t_, base_, n, [&](std::size_t i, const HorizonMap& m) { acc.addDirection(i, m.angleDeg); });
                    const ApertureMaps a = acc.finish();
                    vis = Grid<float>(a.radiusDeg.width(), a.radiusDeg.height());
                    for (std::size_t i = 0; i < vis.size(); ++i) {
                        const double r = a.radiusDeg.data()[i];
                        if (std::isnan(r)) {
                            vis.data()[i] = static_cast<float>(r);
                            continue;
                        }
                        const double cosD = a.bentEast.data()[i] * s.east + a.bentNorth.data()[i] * s.north + a.bentUp.data()[i] * s.up;
                        const double d = std::acos(std::clamp(cosD, -1.0, 1.0));
                        const double rRad = r * std::numbers::pi / 180;
                        const double area = smooth ? capIntersectionAreaSmoothSr(sunRadiusRad, rRad, d)
                                                   : capIntersectionAreaSr(sunRadiusRad, rRad, d);
                        vis.data()[i] = static_cast<float>(area / capAreaSr(sunRadiusRad));
                    }
                });
                add(smooth ? "aperture smoothstep" : "aperture exact", "N=" + std::to_string(n), sec, "sun_visibility_mae",
                    maeAgainst(sampleOf(vis), truthVis_), "N sweeps + aperture + covered fraction of the sun cap");
            }
        }
    }

    /// The sun under --quality auto and full, as `demlight sun` runs it: computeSunFrame with the
    /// distance this sun needs (auto) or the plan's DEM diagonal (full). One sun azimuth over the
    /// crop, so the frame is one sweep at that azimuth; its horizons (for the horizon panel) are
    /// that sweep, repeated untimed.
    void qualitySunRows(const SunField& field) {
        for (const Quality q : {Quality::Auto, Quality::Full}) {
            const SunFrameParams fp =
                planSunFrameParams(planScene(t_, q, QualityBudget{}), kSunDiameterDeg, base_.refraction);
            SunFrame frame;
            const double s = medianSeconds(o_.repeats, [&] { frame = computeSunFrame(t_, normals_, field, fp); });
            HorizonParams hp = base_;
            hp.maxDistanceM = frame.maxDistanceM;
            hp.curvature = fp.curvature;
            hp.directionToleranceDeg = fp.directionToleranceDeg;
            hp.directionToleranceFloorDeg = fp.directionToleranceFloorDeg;
            const std::vector<float> h = sampleOf(sweepHorizon(t_, hp).angleDeg);
            const std::string method = "quality " + std::string(qualityName(q));
            const std::string params = fmt("sun %.1f km", frame.maxDistanceM / 1000);
            const std::string notes = q == Quality::Auto ? "default: the distance this sun needs (sunSearchDistanceM)"
                                                         : "full: the DEM diagonal";
            sunPair(method, params, s, h, sampleOf(frame.light.visibility), notes);
            add(method, params, s, "sun_irradiance_mae", maeAgainst(sampleOf(frame.light.irradiance), truthIrr_), notes);
        }
    }

    /// The sky under --quality auto and full, as `demlight sky` runs it: the plan's directions,
    /// distance, curvature and scan-direction tolerance.
    void qualitySkyRows() {
        for (const Quality q : {Quality::Auto, Quality::Full}) {
            const ScenePlan plan = planScene(t_, q, QualityBudget{});
            const auto n = static_cast<std::size_t>(plan.skyDirections);
            HorizonParams hp = planIntegralParams(t_, plan, n, base_.refraction);
            SkyMaps maps;
            const double s = medianSeconds(o_.repeats, [&] {
                SkyAccumulator acc(normals_.east, normals_.north, normals_.up, n, {});
                sweepDirections(t_, hp, n, [&](std::size_t i, const HorizonMap& m) { acc.addDirection(i, m.angleDeg); });
                maps = acc.finish(0.2);
            });
            add("quality " + std::string(qualityName(q)), fmt("sky N=%.0f ", static_cast<double>(n)) + fmt("%.1f km", plan.maxDistanceM / 1000),
                s, "sky_K_mae", maeAgainst(sampleOf(maps.skyK), refK_),
                q == Quality::Auto ? "default: scene plan" : "full: DEM diagonal, 0.01 deg scan tolerance");
        }
    }

    void skyRows() {
        qualitySkyRows();
        add("sky reference", "dense", refSkyS_, "sky_K_mae", 0,
            "reference itself: error 0 by definition; plotted at the chart floor; " + std::to_string(o_.referenceAzimuths) +
                " ray-marched azimuths timed on the sample");
        for (std::size_t n : {4u, 8u, 16u, 32u, 64u}) {
            // Float horizons for every N; at the default N also both 16-bit storages.
            for (const int variant : {0, 1, 2}) {
                if (variant > 0 && n != kFixedSkyDirections) continue;
                const FixedRange range = variant == 1 ? FixedRange::Seed0To90 : FixedRange::Signed;
                SkyMaps maps;
                const double s = medianSeconds(o_.repeats, [&] {
                    SkyAccumulator acc(normals_.east, normals_.north, normals_.up, n, {});
                    sweepDirections(t_, base_, n, [&](std::size_t i, const HorizonMap& m) {
                        acc.addDirection(i, variant == 0 ? m.angleDeg : fixed16RoundTrip(m.angleDeg, range));
                    });
                    maps = acc.finish(0.2);
                });
                const std::string params = "N=" + std::to_string(n);
                if (variant == 0)
                    add("sky sweep", params, s, "sky_K_mae", maeAgainst(sampleOf(maps.skyK), refK_));
                else
                    add("fixed16 sky sweep", params + (variant == 1 ? " unsigned 0..90" : " signed"), s, "sky_K_mae",
                        maeAgainst(sampleOf(maps.skyK), refK_),
                        variant == 1 ? "unsigned range: negative horizons stored as 0; 2 B/cell/direction"
                                     : "signed range -90..90; 2 B/cell/direction");
            }
        }
        Grid<float> hemi;
        HemisphereParams hp;
        hp.skyRadiance = 1.0;
        hp.groundIrradiance = 0.0;
        const double s = medianSeconds(o_.repeats, [&] { hemi = applyHemisphereLight(normals_.up, hp, nullptr); });
        add("hemisphere", "sky term", s, "sky_K_mae", maeAgainst(sampleOf(hemi), refK_),
            "(1 + N_up) / 2 with a black ground: K of an unoccluded tilted plane; no shadows");
    }

    const Options& o_;
    std::vector<Row>& rows_;
    std::string name_;
    Terrain t_;
    Normals normals_;
    double cells_ = 0, d0_ = 0, marginM_ = 0;
    HorizonParams base_;
    std::vector<CellIndex> sample_;
    std::vector<double> truthH_, truthVis_, truthIrr_, refK_;
    std::vector<float> refD0H_;
    double refTruthS_ = 0, refD0S_ = 0, refSkyS_ = 0;
};

/// Marks, per (dem, metric), the rows no other row beats in both time and error.
void markPareto(std::vector<Row>& rows) {
    for (Row& a : rows) {
        a.pareto = true;
        for (const Row& b : rows) {
            if (&a == &b || a.dem != b.dem || a.metric != b.metric) continue;
            const bool noWorse = b.nsPerCell <= a.nsPerCell && b.error <= a.error;
            const bool better = b.nsPerCell < a.nsPerCell || b.error < a.error;
            if (noWorse && better) {
                a.pareto = false;
                break;
            }
        }
    }
}

std::string csvField(std::string s) {
    std::replace(s.begin(), s.end(), ',', ';');
    return s;
}

void writeCsv(const std::vector<Row>& rows, const std::string& path) {
    std::ofstream f(path);
    if (!f) throw Error("--out: cannot write " + path);
    f << "method,params,dem,ns_per_cell,error_metric,error_value,pareto,notes\n";
    char num[64];
    for (const Row& r : rows) {
        f << csvField(r.method) << ',' << csvField(r.params) << ',' << csvField(r.dem) << ',';
        std::snprintf(num, sizeof num, "%.4g", r.nsPerCell);
        f << num << ',' << r.metric << ',';
        std::snprintf(num, sizeof num, "%.6g", r.error);
        f << num << ',' << (r.pareto ? 1 : 0) << ',' << csvField(r.notes) << '\n';
    }
}

// ---- --auto-vs-full: the default plan against full on whole DEMs ------------------------------

/// Whole DEMs larger than this (cells a side) are cropped to their centre.
constexpr std::size_t kAutoVsFullMaxSide = 600;
/// Cells sampled for the errors (anywhere in the DEM: every method sees the same DEM).
constexpr std::size_t kAutoVsFullCells = 300;
/// Horizon azimuths: on and off the grid axes, as tests/horizon_realdem_test.cpp.
constexpr double kAutoVsFullAzimuthsDeg[] = {0.0, 37.0, 90.0, 123.4, 200.0, 301.7};
/// Sun elevations of the sun rows (degrees): a low sun that needs a long search, and a high one.
constexpr double kAutoVsFullSunElevationsDeg[] = {5.0, 30.0};

struct AutoVsFullRow {
    std::string dem, product, metric;
    double autoS = 0, fullS = 0;
    double workRatio = 0;  ///< full / auto estimateSweepWork (0 = not estimated)
    double autoError = 0, fullError = 0;
    std::string notes;
};

/// Median and 99th percentile of |max(h, e) - max(ref, e)| where both meet terrain: the statistic
/// of ExpectedError (demlight/lighting/quality.h).
std::pair<double, double> clampedMedianP99(const std::vector<double>& h, const std::vector<double>& ref, double e) {
    std::vector<double> err;
    for (std::size_t i = 0; i < h.size(); ++i)
        if (h[i] > kNoHorizonDeg && ref[i] > kNoHorizonDeg)
            err.push_back(std::abs(std::max(h[i], e) - std::max(ref[i], e)));
    std::sort(err.begin(), err.end());
    if (err.empty()) return {0, 0};
    return {err[err.size() / 2], err[std::min(err.size() - 1, static_cast<std::size_t>(0.99 * static_cast<double>(err.size())))]};
}

void autoVsFull(const Options& o, const std::string& path, std::vector<AutoVsFullRow>& rows) {
    const std::string name = std::filesystem::path(path).stem().string();
    const Terrain t = cropTerrainCentre(loadDem(path).terrain, kAutoVsFullMaxSide, kAutoVsFullMaxSide);
    const Normals normals = computeNormals(t);
    const QualityBudget budget;
    const ScenePlan plans[2] = {planScene(t, Quality::Auto, budget), planScene(t, Quality::Full, budget)};
    std::printf("%s: %zu x %zu cells; auto distance %.0f m, full %.0f m\n", name.c_str(), t.width(), t.height(),
                plans[0].maxDistanceM, plans[1].maxDistanceM);

    const std::vector<CellIndex> cells = sampleValidCells(t, kAutoVsFullCells, kSampleSeed);
    HorizonParams reference;  // full physics: curvature on, the whole DEM
    reference.maxDistanceM = std::numeric_limits<double>::infinity();

    // Horizon: one sweep per azimuth with each plan's parameters; a third run is auto with one
    // scan line per cell (HorizonParams::nearestLine), the cheaper model no plan uses.
    {
        std::vector<double> ref, h[3];
        double s[3] = {0, 0, 0}, work[2] = {0, 0};
        for (double az : kAutoVsFullAzimuthsDeg) {
            reference.azimuthDeg = az;
            for (const HorizonSample& x : referenceHorizonAt(t, reference, cells)) ref.push_back(x.angleDeg);
            for (int q = 0; q < 3; ++q) {
                HorizonParams p = planHorizonParams(plans[q == 1 ? 1 : 0], budget.refraction);
                p.azimuthDeg = az;
                p.nearestLine = q == 2;
                HorizonMap m;
                s[q] += medianSeconds(o.repeats, [&] { m = sweepHorizon(t, p); });
                if (q < 2) work[q] += estimateSweepSteps(t, p);
                for (const CellIndex& c : cells) h[q].push_back(m.angleDeg(c.col, c.row));
            }
        }
        // Both plans in auto's scope, and full in its own (every horizon).
        const double e = plans[0].expectedError.aboveElevationDeg;
        const auto [am, ap] = clampedMedianP99(h[0], ref, e);
        const auto [fm, fp] = clampedMedianP99(h[1], ref, e);
        const auto [fam, fap] = clampedMedianP99(h[1], ref, plans[1].expectedError.aboveElevationDeg);
        const auto [nm, np] = clampedMedianP99(h[2], ref, e);
        const double n = static_cast<double>(std::size(kAutoVsFullAzimuthsDeg));
        rows.push_back({name, "horizon (1 azimuth)", fmt("median abs deg (h >= %g deg)", e), s[0] / n, s[1] / n,
                        work[1] / work[0], am, fm,
                        fmt("p99 auto %.2f", ap) + fmt(" full %.2f deg", fp) +
                            fmt("; full on every horizon: median %.3f", fam) + fmt(" p99 %.2f deg", fap) +
                            fmt("; auto with one scan line: %.4g ms", s[2] / n * 1e3) +
                            fmt(" (full/that %.2f)", s[1] / s[2]) + fmt(" median %.4g", nm) + fmt(" p99 %.2f deg", np)});
    }

    // Sun: a frame as `demlight sun` computes it, at a low and a high sun.
    for (double elevation : kAutoVsFullSunElevationsDeg) {
        const SunField field = SunField::uniform(kSunAzimuthDeg, elevation);
        reference.azimuthDeg = kSunAzimuthDeg;
        const std::vector<HorizonSample> ref = referenceHorizonAt(t, reference, cells);
        double s[3], mae[3], distance[3];
        for (int q = 0; q < 3; ++q) {
            SunFrameParams fp = planSunFrameParams(plans[q == 1 ? 1 : 0], kSunDiameterDeg, budget.refraction);
            fp.nearestLine = q == 2;
            SunFrame frame;
            s[q] = medianSeconds(o.repeats, [&] { frame = computeSunFrame(t, normals, field, fp); });
            double sum = 0;
            for (std::size_t i = 0; i < cells.size(); ++i) {
                const Enu nrm = normals.at(cells[i].col, cells[i].row);
                sum += std::abs(frame.light.visibility(cells[i].col, cells[i].row) -
                                sunVisibilityClamped(nrm, ref[i].angleDeg, kSunAzimuthDeg, elevation, kSunDiameterDeg));
            }
            mae[q] = sum / static_cast<double>(cells.size());
            distance[q] = frame.maxDistanceM;
        }
        rows.push_back({name, fmt("sun at %.0f deg", elevation), "visibility MAE", s[0], s[1], 0, mae[0], mae[1],
                        fmt("distance auto %.1f km", distance[0] / 1000) + fmt(", full %.1f km", distance[1] / 1000) +
                            fmt("; auto with one scan line: %.4g ms", s[2] * 1e3) + fmt(" (full/that %.2f)", s[1] / s[2]) +
                            fmt(" MAE %.4g", mae[2])});
    }

    // Sky: the plan's directions, as `demlight sky` computes it.
    {
        const int m = o.referenceAzimuths;
        std::vector<std::vector<HorizonSample>> dense(static_cast<std::size_t>(m));
        for (int j = 0; j < m; ++j) {
            reference.azimuthDeg = (j + 0.5) * 360.0 / m;
            dense[static_cast<std::size_t>(j)] = referenceHorizonAt(t, reference, cells);
        }
        std::vector<double> refK;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            const auto horizon = [&](double azDeg) {
                const auto j = std::min(static_cast<std::size_t>(azDeg / (360.0 / m)), static_cast<std::size_t>(m - 1));
                return static_cast<double>(dense[j][i].angleDeg);
            };
            refK.push_back(referenceSky(horizon, normals.at(cells[i].col, cells[i].row), m).skyK);
        }
        double s[2], mae[2], work[2];
        for (int q = 0; q < 2; ++q) {
            const auto n = static_cast<std::size_t>(plans[q].skyDirections);
            const HorizonParams hp = planIntegralParams(t, plans[q], n, budget.refraction);
            SkyMaps maps;
            s[q] = medianSeconds(o.repeats, [&] {
                SkyAccumulator acc(normals.east, normals.north, normals.up, n, {});
                sweepDirections(t, hp, n, [&](std::size_t i, const HorizonMap& h) { acc.addDirection(i, h.angleDeg); });
                maps = acc.finish(0.2);
            });
            work[q] = estimateSweepWork(t, plans[q], n, budget.refraction);
            double sum = 0;
            for (std::size_t i = 0; i < cells.size(); ++i) sum += std::abs(maps.skyK(cells[i].col, cells[i].row) - refK[i]);
            mae[q] = sum / static_cast<double>(cells.size());
        }
        rows.push_back({name, "sky", "K MAE", s[0], s[1], work[1] / work[0], mae[0], mae[1],
                        fmt("directions auto %.0f", plans[0].skyDirections) + fmt(", full %.0f", plans[1].skyDirections) +
                            fmt("; reference %.0f azimuths", m)});
    }
}

void writeAutoVsFull(const std::vector<AutoVsFullRow>& rows, const std::string& path) {
    std::ofstream f(path);
    if (!f) throw Error("--out: cannot write " + path);
    f << "dem,product,auto_ms,full_ms,speedup,work_ratio,error_metric,auto_error,full_error,notes\n";
    char line[512];
    std::printf("\n| DEM | product | auto ms | full ms | full/auto time | full/auto work | error | auto | full | notes |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n");
    for (const AutoVsFullRow& r : rows) {
        const std::string work = r.workRatio > 0 ? fmt("%.2f", r.workRatio) : "";
        std::snprintf(line, sizeof line, "%s,%s,%.4g,%.4g,%.3g,%s,%s,%.4g,%.4g,%s\n", csvField(r.dem).c_str(),
                      csvField(r.product).c_str(), r.autoS * 1e3, r.fullS * 1e3, r.fullS / r.autoS, work.c_str(),
                      r.metric.c_str(), r.autoError, r.fullError, csvField(r.notes).c_str());
        f << line;
        std::printf("| %s | %s | %.1f | %.1f | %.2f | %s | %s | %.4g | %.4g | %s |\n", r.dem.c_str(), r.product.c_str(),
                    r.autoS * 1e3, r.fullS * 1e3, r.fullS / r.autoS, work.c_str(), r.metric.c_str(), r.autoError,
                    r.fullError, r.notes.c_str());
    }
}

}  // namespace
}  // namespace demlight

int main(int argc, char** argv) {
    using namespace demlight;
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--dem" && i + 1 < argc) {
            o.dems.push_back(argv[++i]);
        } else if (a == "--out" && i + 1 < argc) {
            o.outDir = argv[++i];
        } else if (a == "--quick") {
            o.quick = true;
        } else if (a == "--auto-vs-full") {
            o.autoVsFull = true;
        } else {
            std::fprintf(stderr, "usage: %s [--auto-vs-full] [--dem PATH ...] [--out DIR] [--quick]\n", argv[0]);
            return 2;
        }
    }
    if (o.quick) o.cropCells = 200, o.sampleCells = 300, o.referenceAzimuths = 120;
    try {
        if (o.autoVsFull) {
            if (o.dems.empty())
                o.dems = {"samples/mount_st_helens_1980_usgs.dem", "samples/rocky_mountain_np_dem.tif",
                          "samples/luxembourg_elev_terra.tif"};
            std::vector<AutoVsFullRow> rows;
            withThreads(kThreads, [&] {
                for (const std::string& path : o.dems) autoVsFull(o, path, rows);
            });
            std::filesystem::create_directories(o.outDir);
            const std::string csv = o.outDir + "/auto_vs_full.csv";
            writeAutoVsFull(rows, csv);
            std::printf("wrote %s (%zu rows)\n", csv.c_str(), rows.size());
            return 0;
        }
        if (o.dems.empty()) o.dems = {"samples/mount_st_helens_1980_usgs.dem"};
        std::vector<Row> rows;
        withThreads(kThreads, [&] {
            for (const std::string& path : o.dems) DemBench(o, path, rows).run();
        });
        markPareto(rows);
        std::filesystem::create_directories(o.outDir);
        const std::string csv = o.outDir + "/tradeoff.csv";
        writeCsv(rows, csv);
        std::printf("wrote %s (%zu rows)\n", csv.c_str(), rows.size());
    } catch (const Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
