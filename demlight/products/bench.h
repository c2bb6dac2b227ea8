// Speed against accuracy on the user's own DEM (`demlight bench`): the horizon methods and plans
// timed on a centred crop (or the whole DEM) and scored against the reference ray march on a
// fixed sample of its cells, the measurement docs/performance.md makes on the bundled and shared
// DEMs (bench/tradeoff_bench.cpp), as a product a user can run.
//
// Every method searches the same distance (the auto plan's on the crop, or the request's), so
// the scores measure the method, not the distance. Errors are |method - reference| in degrees
// over every sampled cell and every azimuth of the row's directions, where the reference meets
// terrain (a horizon of kNoHorizonDeg says nothing about accuracy).
#pragma once

#include "demlight/products/product.h"

#include <cstdint>
#include <string>
#include <vector>

namespace demlight {

struct BenchRequest {
    /// Cells a side of the centred crop; 0 = the whole DEM.
    std::size_t cropCells = 400;
    /// Cells scored against the reference (fewer when the crop has fewer valid cells).
    std::size_t sampleCells = 300;
    /// Direction counts timed per sweep method (N evenly spaced azimuths from 0).
    std::vector<std::size_t> directions = {4, 16, 32};
    /// Timed runs per method; the median counts.
    int repeats = 3;
    /// Search options: threads, refraction, --max-distance (the quality is the row's own).
    SearchRequest search;
};

/// One method or plan on the crop.
struct BenchRow {
    std::string family;   ///< "sweep", "reference" or a peer ("GRASS r.horizon")
    std::string method;   ///< e.g. "quality auto (two lines)"
    std::size_t directions = 0;
    double seconds = 0;   ///< wall time of all directions on the whole crop (median of repeats)
    double nsPerCellPerDirection = 0;
    double medianErrorDeg = 0;  ///< median |horizon - reference| (degrees)
    double p99ErrorDeg = 0;     ///< 99th percentile of the same
    std::size_t scored = 0;     ///< cell-azimuth pairs scored
    bool pareto = false;        ///< no other row is both faster and lower in median error
    std::string notes;
};

/// What the rows were measured on, and the reference a peer is scored against (scoreHorizons).
struct BenchScene {
    Dem crop;                      ///< the crop as its own DEM (heights, georeference)
    double maxDistanceM = 0;       ///< the search distance every method used
    std::vector<CellIndex> sample; ///< the scored cells (crop cells)
    /// Reference horizons (degrees) per azimuth of `referenceAzimuthsDeg`, per sampled cell.
    std::vector<double> referenceAzimuthsDeg;
    std::vector<std::vector<float>> referenceDeg;
    double referenceSecondsPerCellPerDirection = 0;
};

struct BenchResult {
    BenchScene scene;
    std::vector<BenchRow> rows;
};

/// Crops, samples, computes the reference at the azimuths of every direction count, then times
/// and scores the sweep under the auto plan (two scan lines per cell), with one scan line per
/// cell (what the sky integrals use), and the full plan. Progress counts methods.
BenchResult benchProduct(const DemSource& source, const BenchRequest& request, const ProgressFn& progress = {});

/// Scores horizons given at the scene's sample for `directions` evenly spaced azimuths
/// (horizonsDeg[k][i]: azimuth k, sampled cell i; NaN = none) against its reference: sets the
/// row's directions, errors and count. Azimuths must be among the reference's.
void scoreHorizons(const BenchScene& scene, std::size_t directions, const std::vector<std::vector<float>>& horizonsDeg,
                   BenchRow& row);

/// Marks the Pareto front: a row is on it when no other row is both faster (nsPerCellPerDirection)
/// and more accurate (medianErrorDeg), ties counting as neither.
void markPareto(std::vector<BenchRow>& rows);

/// The CSV of the rows (header: family, method, directions, seconds, ns_per_cell_per_direction,
/// median_error_deg, p99_error_deg, scored, pareto, notes).
std::string benchCsv(const std::vector<BenchRow>& rows);

}  // namespace demlight
