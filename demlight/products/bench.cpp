#include "demlight/core/parallel.h"
#include "demlight/products/bench.h"

#include "demlight/core/timing.h"

#include "demlight/lighting/directions.h"
#include "demlight/lighting/quality.h"
#include "demlight/products/horizon.h"
#include "demlight/core/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace demlight {
namespace {

/// The same cells every run (as bench/tradeoff_bench.cpp's sample).
constexpr std::uint64_t kSampleSeed = 4242;
/// Sampled cells are at least the search distance from the crop's edges, capped at this share of
/// its shorter side, so that each has terrain around it (the crop edge truncates every method,
/// and the reference, alike beyond that).
constexpr double kMarginSideFraction = 1.0 / 6.0;

/// The q-quantile (0..1) of `v` by the nearest rank (v is sorted in place).
double quantile(std::vector<double>& v, double q) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::clamp<std::size_t>(k, 1, v.size()) - 1];
}

/// Index of `azimuthDeg` among the reference's azimuths; throws when it is not one.
std::size_t referenceIndex(const BenchScene& scene, double azimuthDeg) {
    for (std::size_t k = 0; k < scene.referenceAzimuthsDeg.size(); ++k)
        if (std::abs(scene.referenceAzimuthsDeg[k] - azimuthDeg) < 1e-9) return k;
    throw Error("bench: azimuth " + formatNumber(azimuthDeg) + " has no reference");
}

}  // namespace

void scoreHorizons(const BenchScene& scene, std::size_t directions, const std::vector<std::vector<float>>& horizonsDeg,
                   BenchRow& row) {
    const std::vector<double> azimuths = evenAzimuthsDeg(directions);
    if (horizonsDeg.size() != azimuths.size()) throw Error("bench: horizons for " + std::to_string(azimuths.size()) +
                                                           " azimuths expected, got " + std::to_string(horizonsDeg.size()));
    std::vector<double> errors;
    for (std::size_t k = 0; k < azimuths.size(); ++k) {
        const std::vector<float>& ref = scene.referenceDeg[referenceIndex(scene, azimuths[k])];
        for (std::size_t i = 0; i < scene.sample.size(); ++i) {
            const float r = ref[i], h = horizonsDeg[k][i];
            // A reference of kNoHorizonDeg met no terrain: nothing to score.
            if (std::isnan(r) || r <= static_cast<float>(kNoHorizonDeg) || std::isnan(h)) continue;
            errors.push_back(std::abs(static_cast<double>(h) - r));
        }
    }
    row.directions = directions;
    row.scored = errors.size();
    std::vector<double> sorted = errors;
    row.medianErrorDeg = quantile(sorted, 0.5);
    row.p99ErrorDeg = quantile(sorted, 0.99);
}

void markPareto(std::vector<BenchRow>& rows) {
    for (BenchRow& a : rows) {
        a.pareto = std::none_of(rows.begin(), rows.end(), [&](const BenchRow& b) {
            return &a != &b && b.nsPerCellPerDirection <= a.nsPerCellPerDirection && b.medianErrorDeg <= a.medianErrorDeg &&
                   (b.nsPerCellPerDirection < a.nsPerCellPerDirection || b.medianErrorDeg < a.medianErrorDeg);
        });
    }
}

std::string benchCsv(const std::vector<BenchRow>& rows) {
    std::ostringstream out;
    out << "family,method,directions,seconds,ns_per_cell_per_direction,median_error_deg,p99_error_deg,scored,pareto,notes\n";
    const auto quoted = [](const std::string& s) {
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    };
    for (const BenchRow& r : rows)
        out << quoted(r.family) << ',' << quoted(r.method) << ',' << r.directions << ',' << formatNumber(r.seconds) << ','
            << formatNumber(r.nsPerCellPerDirection) << ',' << formatNumber(r.medianErrorDeg) << ','
            << formatNumber(r.p99ErrorDeg) << ',' << r.scored << ',' << (r.pareto ? 1 : 0) << ',' << quoted(r.notes) << '\n';
    return out.str();
}

BenchResult benchProduct(const DemSource& source, const BenchRequest& request, const ProgressFn& progress) {
    return withThreads(request.search.threads, [&] {
        if (request.directions.empty()) throw FieldError("directions", ": give at least one direction count");
        for (std::size_t n : request.directions)
            if (n < 1 || n > 4096) throw FieldError("directions", " " + std::to_string(n) + ": must be 1..4096");
        if (request.sampleCells < 1) throw FieldError("sampleCells", ": must be at least 1");

        BenchResult result;
        BenchScene& scene = result.scene;
        // Step 1: the crop, as its own DEM (what a user's job on that area would read).
        CellWindow window = source.whole();
        if (request.cropCells > 0) {
            const std::size_t w = std::min(request.cropCells, source.width()), h = std::min(request.cropCells, source.height());
            const std::size_t c0 = (source.width() - w) / 2, r0 = (source.height() - h) / 2;
            window = {c0, r0, c0 + w, r0 + h};
        }
        scene.crop = source.read(window);
        const Terrain& t = scene.crop.terrain;
        const double cells = static_cast<double>(t.width() * t.height());

        // Step 2: one search distance for every method: the auto plan's on the crop (or the user's).
        SearchRequest autoSearch = request.search;
        autoSearch.quality = Quality::Auto;
        const ScenePlan autoPlan = planFor(autoSearch, t);
        scene.maxDistanceM = autoPlan.maxDistanceM;
        SearchRequest fullSearch = autoSearch;
        fullSearch.quality = Quality::Full;
        fullSearch.maxDistanceM = scene.maxDistanceM;
        const ScenePlan fullPlan = planFor(fullSearch, t);

        // Step 3: the sample, and the reference (full physics: curvature and refraction on) at the
        // azimuths of every direction count.
        const std::size_t mid = t.height() / 2;
        const double sideM = std::min(t.cellWidthM[mid] * static_cast<double>(t.width()),
                                      t.cellHeightM[mid] * static_cast<double>(t.height()));
        const double marginM = std::isfinite(scene.maxDistanceM) ? std::min(scene.maxDistanceM, kMarginSideFraction * sideM)
                                                                 : kMarginSideFraction * sideM;
        scene.sample = sampleValidCells(t, request.sampleCells, kSampleSeed, marginM);
        if (scene.sample.empty()) scene.sample = sampleValidCells(t, request.sampleCells, kSampleSeed);
        if (scene.sample.empty()) throw Error("bench: the crop has no valid cells");
        for (std::size_t n : request.directions)
            for (double az : evenAzimuthsDeg(n))
                if (std::none_of(scene.referenceAzimuthsDeg.begin(), scene.referenceAzimuthsDeg.end(),
                                 [&](double a) { return std::abs(a - az) < 1e-9; }))
                    scene.referenceAzimuthsDeg.push_back(az);

        const std::size_t methods = 3 * request.directions.size();
        ProgressCounter counter(progress, "bench", scene.referenceAzimuthsDeg.size() + methods);
        HorizonParams refParams = horizonParams(fullSearch, fullPlan);
        refParams.maxDistanceM = scene.maxDistanceM;
        refParams.curvature = true;
        const auto refStart = std::chrono::steady_clock::now();
        for (double az : scene.referenceAzimuthsDeg) {
            refParams.azimuthDeg = az;
            std::vector<float> h;
            for (const HorizonSample& s : referenceHorizonAt(t, refParams, scene.sample)) h.push_back(s.angleDeg);
            scene.referenceDeg.push_back(std::move(h));
            counter.advance();
            counter.throwIfCancelled();
        }
        scene.referenceSecondsPerCellPerDirection =
            secondsSince(refStart) / static_cast<double>(scene.sample.size() * scene.referenceAzimuthsDeg.size());

        BenchRow reference;
        reference.family = "reference";
        reference.method = "ray march (on the sample)";
        reference.directions = request.directions.back();
        reference.nsPerCellPerDirection = scene.referenceSecondsPerCellPerDirection * 1e9;
        reference.seconds = scene.referenceSecondsPerCellPerDirection * cells * static_cast<double>(reference.directions);
        reference.scored = scene.sample.size() * scene.referenceAzimuthsDeg.size();
        reference.notes = "error 0 by definition; timed on the sample and scaled to the crop";
        result.rows.push_back(reference);

        // Step 4: the sweeps, each direction count timed on the whole crop and scored on the sample.
        struct Variant {
            std::string method, notes;
            HorizonParams params;
        };
        HorizonParams twoLines = horizonParams(autoSearch, autoPlan);
        HorizonParams oneLine = twoLines;
        oneLine.nearestLine = true;
        HorizonParams full = horizonParams(fullSearch, fullPlan);
        const std::vector<Variant> variants = {
            {"quality auto (two lines)", "what demlight horizon and sun run by default", twoLines},
            {"nearest line", "auto with one scan line per cell (as the sky integrals)", oneLine},
            {"quality full", "--quality full at the same distance (0.01 deg scan tolerance)", full},
        };
        for (const Variant& v : variants) {
            for (std::size_t n : request.directions) {
                std::vector<Grid<float>> maps(n);
                const double s = medianSeconds(request.repeats, [&] {
                    sweepDirections(t, v.params, n, [&](std::size_t i, const HorizonMap& m) { maps[i] = m.angleDeg; });
                });
                std::vector<std::vector<float>> atSample(n);
                for (std::size_t k = 0; k < n; ++k)
                    for (const CellIndex& c : scene.sample) atSample[k].push_back(maps[k](c.col, c.row));
                BenchRow row;
                row.family = "sweep";
                row.method = v.method;
                row.seconds = s;
                row.nsPerCellPerDirection = s / cells / static_cast<double>(n) * 1e9;
                row.notes = v.notes;
                scoreHorizons(scene, n, atSample, row);
                result.rows.push_back(row);
                counter.advance();
                counter.throwIfCancelled();
            }
        }
        return result;
    });
}

}  // namespace demlight
