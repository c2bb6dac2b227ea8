// Horizon sweep: upper convex hulls along lines parallel to the azimuth (Dozier 1981; Timonen &
// Westerholm 2010), with the curvature trick of docs/design.md §4. See demlight/lighting/horizon.h.
#include "demlight/lighting/horizon.h"

#include "demlight/lighting/sweep/combine.h"
#include "demlight/lighting/sweep/line_geometry.h"
#include "demlight/lighting/sweep/regions.h"
#include "demlight/lighting/sweep/valid_cells.h"
#include "demlight/lighting/sweep/walk.h"

#include "demlight/core/angles.h"
#include "demlight/core/error.h"
#include "demlight/core/fast_math.h"
#include "demlight/core/parallel.h"
#include "demlight/core/simd.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <numbers>
#include <string>
#include <type_traits>

namespace demlight {

using sweep::combineRow;
using sweep::kLinesPerBlock;
using sweep::LineGeometry;
using sweep::makeGeometry;
using sweep::ValidCells;
using sweep::walkLineBlock;

double inverseEffectiveRadius(const HorizonParams& params) {
    return params.curvature ? (1.0 - params.refraction) / kEarthRadiusM : 0.0;
}

void validateHorizonParams(const Terrain& terrain, const HorizonParams& p) {
    if (terrain.heightsM.empty()) throw Error("horizon: the terrain has no cells");
    if (terrain.cellWidthM.size() != terrain.height() || terrain.cellHeightM.size() != terrain.height())
        throw Error("horizon: terrain cell sizes must have one entry per row");
    for (std::size_t r = 0; r < terrain.height(); ++r) {
        if (!(terrain.cellWidthM[r] > 0.0) || !(terrain.cellHeightM[r] > 0.0) ||
            !std::isfinite(terrain.cellWidthM[r]) || !std::isfinite(terrain.cellHeightM[r]))
            throw Error("horizon: terrain cell sizes must be positive and finite (row " +
                        std::to_string(r) + ")");
    }
    if (!std::isfinite(p.azimuthDeg))
        throw Error("horizon: azimuth must be a finite number of degrees, got " + std::to_string(p.azimuthDeg));
    if (!(p.maxDistanceM > 0.0))
        throw Error("horizon: max distance must be > 0 metres, got " + std::to_string(p.maxDistanceM));
    if (!(p.refraction >= 0.0 && p.refraction < 1.0))
        throw Error("horizon: refraction coefficient must be in [0, 1), got " + std::to_string(p.refraction));
    if (!(p.directionToleranceFloorDeg >= 0.0))
        throw Error("horizon: direction tolerance floor must be >= 0 degrees, got " +
                    std::to_string(p.directionToleranceFloorDeg));
    if (!(p.directionToleranceDeg >= 0.0))
        throw Error("horizon: direction tolerance must be >= 0 degrees (0 = automatic), got " +
                    std::to_string(p.directionToleranceDeg));
    if (p.nearFieldSteps < 0 || p.nearFieldSteps > kMaxNearFieldSteps)
        throw Error("horizon: near field must be 0 to " + std::to_string(kMaxNearFieldSteps) + " steps, got " +
                    std::to_string(p.nearFieldSteps));
    if (p.window) {
        const CellWindow& w = *p.window;
        if (w.col0 >= w.col1 || w.row0 >= w.row1 || w.col1 > terrain.width() || w.row1 > terrain.height())
            throw Error("horizon: window must be a non-empty part of the " + std::to_string(terrain.width()) +
                        " x " + std::to_string(terrain.height()) + " grid");
    }
}

ReliefSearch reliefSearch(const Terrain& terrain, double elevationDeg) {
    const FullGridRef g = fullGrid(terrain);  // a tile's search is its DEM's
    const auto [lo, hi] = g.heightRangeM();
    ReliefSearch s;
    s.reliefM = lo <= hi ? static_cast<double>(hi - lo) : 0.0;  // no valid height: nothing occludes
    s.byReliefM = s.reliefM / std::tan(elevationDeg * kDegToRad);
    const double diagonal = diagonalM(g);
    s.wholeDem = s.byReliefM >= kWholeDemShareOfDiagonal * diagonal;
    s.distanceM = std::max(g.minCellM(), s.wholeDem ? diagonal : s.byReliefM);
    return s;
}

double defaultMaxDistanceM(const Terrain& terrain) {
    const auto [lo, hi] = fullGrid(terrain).heightRangeM();
    if (lo > hi) throw Error("horizon: the DEM has no valid heights");
    return reliefSearch(terrain, kDefaultLowestElevationDeg).distanceM;
}

HorizonMap sweepHorizon(const Terrain& terrain, const HorizonParams& params, ProgressCounter* progress) {
    HorizonMap out;
    SweepBuffers buffers;
    sweepHorizonInto(terrain, params, out, buffers, progress);
    return out;
}

std::size_t sweepHorizonInto(const Terrain& terrain, const HorizonParams& params, HorizonMap& out,
                             SweepBuffers& buffers, ProgressCounter* progress) {
    const std::vector<SweepRegion> regions = sweep::fullGridRegions(terrain, params);
    const FullGridRef full = fullGrid(terrain);
    const CellWindow cells = cellsOnFullGrid(terrain);
    const double invR = inverseEffectiveRadius(params);
    // Eight lines at once on the AVX-512 path (the portable one serves one line at a time).
    const bool eightAtOnce = simdPath() == SimdPath::Avx512;

    // Reused grids are refilled in place, by rows in parallel (no fresh pages to fault in).
    const auto reset = [&](auto& grid, auto fill) {
        if (grid.width() == terrain.width() && grid.height() == terrain.height()) {
            parallelFor(0, grid.height(), [&](std::size_t row) {
                std::fill_n(grid.rowPtr(row), grid.width(), fill);
            }, 64);
        } else {
            grid = std::remove_reference_t<decltype(grid)>(terrain.width(), terrain.height(), fill);
        }
    };
    reset(out.angleDeg, std::numeric_limits<float>::quiet_NaN());
    if (params.truncationFlags) {
        reset(out.truncated, std::uint8_t{0});
    } else {
        out.truncated = Grid<std::uint8_t>();
    }
    // NaN until written, so a cell no line served would show up as NaN in the tests. Plane B is
    // read only where two lines serve a cell.
    Grid<float>& planeB = buffers.planeB;
    if (!params.nearestLine) reset(planeB, std::numeric_limits<float>::quiet_NaN());

    for (const SweepRegion& region : regions) {
        const LineGeometry geo = makeGeometry(full, cells, region, params.maxDistanceM, params.nearestLine,
                                              params.nearFieldSteps, params.farFieldCrossings);
        const long nLines = geo.kLast - geo.kFirst + 1;
        const std::size_t nBlocks = static_cast<std::size_t>((nLines + static_cast<long>(kLinesPerBlock) - 1) /
                                                             static_cast<long>(kLinesPerBlock));
        const CellWindow& w = region.window;
        const ValidCells valid(terrain, geo.xMajor, buffers.validBits[geo.xMajor ? 0 : 1]);
        // Every served cell of plane A is written; plane B only where frac > 0, read only there.
        parallelFor(0, nBlocks, [&](std::size_t blockIndex) {
            if (progress && progress->cancelled()) return;
            const long kBegin = geo.kFirst + static_cast<long>(blockIndex * kLinesPerBlock);
            const long kEnd = std::min(kBegin + static_cast<long>(kLinesPerBlock), geo.kLast + 1);
            walkLineBlock(terrain, geo, invR, params.maxDistanceM, kBegin, kEnd, out.angleDeg.data(), planeB.data(),
                          valid, eightAtOnce);
        });
        if (progress) progress->throwIfCancelled();
        parallelFor(w.row0, w.row1, [&](std::size_t row) {
            combineRow(geo, terrain, full, params.maxDistanceM, invR, row, w, cells, out.angleDeg.data(), planeB.data(),
                       params.truncationFlags ? out.truncated.data() : nullptr);
        }, 16);
        if (progress) {
            progress->advance((w.col1 - w.col0) * (w.row1 - w.row0));
            progress->throwIfCancelled();
        }
    }
    return regions.size();
}

}  // namespace demlight
