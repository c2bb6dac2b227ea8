// Random grids for the sky's and the aperture's exact passes: cells of every slope whose tangent
// plane rises above many of their horizons.
#pragma once

#include "demlight/core/grid.h"

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace demlight {

/// Normals (as float grids hold them) and the horizons of `directions` even sectors.
struct RisingPlaneGrids {
    Grid<float> east, north, up;
    std::vector<Grid<float>> horizonsDeg;
    std::vector<const Grid<float>*> horizonPointers() const {
        std::vector<const Grid<float>*> out;
        for (const auto& g : horizonsDeg) out.push_back(&g);
        return out;
    }
};

/// w x h cells sloping 0-80 deg, every seventh 88-89.9 deg, in any aspect; 70 % of the horizons
/// within 10 deg of the tangent plane's elevation at a random azimuth of their sector, the rest
/// anywhere in -85..85 deg; cell (5, 5) of the first direction is a void (NaN).
inline RisingPlaneGrids risingPlaneGrids(std::size_t w, std::size_t h, int directions, std::mt19937_64& rng) {
    constexpr double kDeg = std::numbers::pi / 180.0;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    RisingPlaneGrids g{Grid<float>(w, h), Grid<float>(w, h), Grid<float>(w, h),
                       std::vector<Grid<float>>(static_cast<std::size_t>(directions), Grid<float>(w, h))};
    for (std::size_t r = 0; r < h; ++r)
        for (std::size_t c = 0; c < w; ++c) {
            const double slope = ((r * w + c) % 7 == 0 ? 88.0 + 1.9 * unit(rng) : 80.0 * unit(rng)) * kDeg;
            const double aspect = 360.0 * unit(rng) * kDeg;
            const double e = std::sin(slope) * std::sin(aspect), n = std::sin(slope) * std::cos(aspect);
            const double u = std::cos(slope);
            g.east(c, r) = static_cast<float>(e);
            g.north(c, r) = static_cast<float>(n);
            g.up(c, r) = static_cast<float>(u);
            for (int i = 0; i < directions; ++i) {
                const double az = (i + unit(rng) - 0.5) * 360.0 / directions * kDeg;
                const double plane = std::atan(-(e * std::sin(az) + n * std::cos(az)) / u) / kDeg;
                g.horizonsDeg[static_cast<std::size_t>(i)](c, r) =
                    static_cast<float>(unit(rng) < 0.7 ? plane + 20.0 * (unit(rng) - 0.5) : 170.0 * unit(rng) - 85.0);
            }
        }
    g.horizonsDeg[0](5, 5) = std::numeric_limits<float>::quiet_NaN();
    return g;
}

}  // namespace demlight
