// The float hull kernel against the double one on the four grid-axis directions of whole DEMs
// and surface models: the lines laid out as the sweep lays them along an axis (columns with
// their rows' heights as distances, rows each at its own cell width, walked from each edge), the
// slopes of hullSlopes (the dispatched float kernel) and of hullSlopesReference (double) turned
// into angles as the sweep's combine does; |difference| in degrees over the cells where both
// see terrain (median, p99.9, max), and the cells where one sees terrain and the other not.
// With --sweep, also the library's sweep (true azimuths 0/90/180/270, no near field, the whole
// DEM) against the double lines: on geographic grids the grid axes are those azimuths, so this
// is the sweep's own change; elsewhere the sweep takes other lines and the row is left out.
// With --max-distance L, each line is cut into chunks of L metres from its far edge (as the
// range-limited sweep cuts it) and each chunk walked on its own: the error of the kernel's part of
// a range-limited sweep (the previous chunk's part is added in double by the sweep, so the
// difference of the maxima is at most this one).
// Usage: demlight_axis_precision_bench [--sweep] [--max-distance L] DEM ...
#include "demlight/core/angles.h"
#include "demlight/core/fast_math.h"
#include "demlight/geo/dem.h"
#include "demlight/lighting/horizon.h"
#include "demlight/lighting/hull_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <vector>

namespace {

using namespace demlight;

/// Lines along columns (walked from row 0 or from the last row) or rows (from column 0 or the last).
struct Direction {
    const char* name;
    double trueAzimuthDeg;  // on a geographic grid
    bool alongRows, fromHighEnd;
};
constexpr Direction kDirections[] = {
    {"columns from the top (N)", 0.0, false, false},
    {"rows from the right (E)", 90.0, true, true},
    {"columns from the bottom (S)", 180.0, false, true},
    {"rows from the left (W)", 270.0, true, false},
};

float toAngle(float slope) {
    if (std::isnan(slope)) return slope;
    return slope == -std::numeric_limits<float>::infinity()
               ? static_cast<float>(kNoHorizonDeg)
               : static_cast<float>(fastAtan(static_cast<double>(slope)) * kRadToDeg);
}

/// Every cell's angle from its line, through the float kernel or the double reference; with a
/// finite maxDistanceM, each chunk of the line (floor(sigma / maxDistanceM)) walked on its own.
std::vector<float> lineAngles(const Terrain& t, const Direction& d, bool reference,
                              double maxDistanceM = std::numeric_limits<double>::infinity()) {
    const std::size_t w = t.width(), h = t.height();
    const std::size_t lines = d.alongRows ? h : w, n = d.alongRows ? w : h;
    const auto cellIndex = [&](std::size_t i, std::size_t b) {
        const std::size_t m = d.fromHighEnd ? n - 1 - i : i;
        return d.alongRows ? b * w + m : m * w + b;
    };
    std::vector<double> sigma(n, 0.0);
    for (std::size_t i = 1; i < n; ++i)
        sigma[i] = d.alongRows ? static_cast<double>(i) : sigma[i - 1] + t.cellHeightM[d.fromHighEnd ? n - i : i - 1];
    std::vector<float> heights(n * lines), slopes(n * lines), angles(w * h);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t b = 0; b < lines; ++b) heights[i * lines + b] = t.heightsM.data()[cellIndex(i, b)];
    HullScratch scratch;
    HullGeometry g;
    g.invRadius = inverseEffectiveRadius(HorizonParams{});
    // Samples [s0, s1) of lines [b0, b1) (all lines share the distances, or one line).
    const auto walk = [&](std::size_t s0, std::size_t s1, std::size_t b0, std::size_t b1) {
        g.sigmaM.assign(sigma.begin() + static_cast<std::ptrdiff_t>(s0), sigma.begin() + static_cast<std::ptrdiff_t>(s1));
        for (double& x : g.sigmaM) x -= sigma[s0];
        g.lineScale.clear();
        if (d.alongRows) g.lineScale.assign(t.cellWidthM.begin() + static_cast<std::ptrdiff_t>(b0),
                                            t.cellWidthM.begin() + static_cast<std::ptrdiff_t>(b1));
        else g.spacingM = sigma[n - 1] / static_cast<double>(std::max<std::size_t>(n - 1, 1));
        const HullBlock block{heights.data() + s0 * lines + b0, slopes.data() + s0 * lines + b0, lines, b1 - b0};
        if (reference)
            hullSlopesReference(g, block, scratch);
        else
            hullSlopes(g, block, scratch);
    };
    // Chunks of one set of distances (scale: a row's cell width along rows, else 1).
    const auto chunks = [&](std::size_t b0, std::size_t b1, double scale) {
        if (!std::isfinite(maxDistanceM)) return walk(0, n, b0, b1);
        for (std::size_t s0 = 0, s1; s0 < n; s0 = s1) {
            const double c = std::floor(sigma[s0] * scale / maxDistanceM);
            for (s1 = s0 + 1; s1 < n && std::floor(sigma[s1] * scale / maxDistanceM) == c;) ++s1;
            walk(s0, s1, b0, b1);
        }
    };
    if (d.alongRows && std::isfinite(maxDistanceM)) {
        for (std::size_t b = 0; b < lines; ++b) chunks(b, b + 1, t.cellWidthM[b]);
    } else {
        chunks(0, lines, 1.0);
    }
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t b = 0; b < lines; ++b) angles[cellIndex(i, b)] = toAngle(slopes[i * lines + b]);
    return angles;
}

void report(const char* dem, const char* what, const std::vector<float>& a, const std::vector<float>& b) {
    std::vector<double> diffs;
    std::size_t oneSided = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const float x = a[i], y = b[i];
        if (std::isnan(x) || std::isnan(y)) {
            oneSided += std::isnan(x) != std::isnan(y);
            continue;
        }
        const bool noneX = x == static_cast<float>(kNoHorizonDeg), noneY = y == static_cast<float>(kNoHorizonDeg);
        if (noneX || noneY) {
            oneSided += noneX != noneY;
            continue;
        }
        diffs.push_back(std::abs(static_cast<double>(x) - y));
    }
    std::sort(diffs.begin(), diffs.end());
    const auto at = [&](double q) {
        return diffs.empty() ? 0.0 : diffs[std::min(diffs.size() - 1, static_cast<std::size_t>(q * diffs.size()))];
    };
    std::printf("| %s | %s | %zu | %.1e | %.1e | %.1e | %zu |\n", dem, what, diffs.size(), at(0.5), at(0.999),
                diffs.empty() ? 0.0 : diffs.back(), oneSided);
}

}  // namespace

int main(int argc, char** argv) {
    bool sweep = false;
    double maxDistanceM = std::numeric_limits<double>::infinity();
    std::vector<std::string> dems;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--sweep") == 0)
            sweep = true;
        else if (std::strcmp(argv[i], "--max-distance") == 0 && i + 1 < argc)
            maxDistanceM = std::stod(argv[++i]);
        else
            dems.emplace_back(argv[i]);
    }
    if (dems.empty()) {
        std::fprintf(stderr, "usage: %s [--sweep] [--max-distance L] DEM ...\n", argv[0]);
        return 2;
    }
    try {
        std::printf("| DEM | lines | cells | median deg | p99.9 deg | max deg | one side only |\n|---|---|---|---|---|---|---|\n");
        for (const std::string& path : dems) {
            const Dem dem = loadDem(path);
            const Terrain& t = dem.terrain;
            const std::string name = path.substr(path.find_last_of('/') + 1);
            for (const Direction& d : kDirections) {
                const std::vector<float> ref = lineAngles(t, d, true, maxDistanceM);
                report(name.c_str(), d.name, lineAngles(t, d, false, maxDistanceM), ref);
                if (sweep && dem.crs.geographic && !std::isfinite(maxDistanceM)) {
                    HorizonParams p;
                    p.azimuthDeg = d.trueAzimuthDeg;
                    const HorizonMap map = sweepHorizon(t, p);
                    const std::vector<float> swept(map.angleDeg.data(), map.angleDeg.data() + map.angleDeg.size());
                    report(name.c_str(), ("sweep, azimuth " + std::to_string(static_cast<int>(d.trueAzimuthDeg))).c_str(),
                           swept, ref);
                }
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}
