// "Model no more than a scene needs" (DESIGN §3): from the scene and an error budget, choose the
// search distance, curvature, scan-direction tolerance, number of sky directions and sun-position
// granularity. `auto` spends only what the budget needs; `full` turns every effect on at its
// finest setting. The plan is recorded in output metadata and printed with --verbose.
#pragma once

#include "lighting/sky.h"
#include "src/terrain.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace demlight {

enum class Quality { Auto, Full };

/// "auto" or "full"; throws Error naming the option otherwise.
Quality parseQuality(std::string_view name);
std::string_view qualityName(Quality q);

/// Sky and aperture directions used by `auto`: the measured default (lighting/sky.h).
inline constexpr int kAutoSkyDirections = static_cast<int>(kDefaultSkyDirections);
/// Directions used by `full`.
inline constexpr int kFullSkyDirections = 64;

struct QualityBudget {
    /// Horizon angle error the user accepts from modelling choices (degrees).
    double toleranceDeg = 0.1;
    /// Lowest sun (or sky) elevation whose shadows matter (degrees); sets the search distance.
    double lowestElevationDeg = 2.0;
    /// Effective-radius refraction coefficient k the user asked for.
    double refraction = 0.13;
};

struct ScenePlan {
    Quality quality = Quality::Auto;
    double maxDistanceM = 0;          ///< horizon search distance (metres)
    bool curvature = true;            ///< earth curvature and refraction in sight lines
    double directionToleranceDeg = 0; ///< sweep region split tolerance (0 = the sweep's automatic rule)
    int skyDirections = kAutoSkyDirections;           ///< sectors for sky and aperture integrals
    std::size_t sunLatticeStepCells = 64;  ///< SPA evaluated every this many cells
    /// One line per choice, "name=value (why)", for metadata and --verbose.
    std::vector<std::string> reasons;
};

/// Chooses the plan. Rules for `auto`:
///  - search distance: relief / tan(lowestElevation), capped by the DEM diagonal: terrain
///    farther away cannot rise above that elevation;
///  - curvature: on unless the drop over the whole search distance, d / (2 R_eff), is below a
///    tenth of the tolerance (it costs nothing in the sweep, so only tiny scenes turn it off);
///  - direction tolerance: the sweep's automatic rule (one cell of sideways drift at the search
///    distance), which keeps the direction error's effect on horizons below the cell scale;
///  - sky directions: kAutoSkyDirections; sun lattice: 64 cells (the sun moves 0.004 deg per km).
/// `full`: the DEM diagonal as distance, curvature on, 0.01 deg direction tolerance,
/// kFullSkyDirections, a 16-cell sun lattice.
ScenePlan planScene(const Terrain& terrain, Quality quality, const QualityBudget& budget);

}  // namespace demlight
