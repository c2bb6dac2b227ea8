// The real DEMs of ../shared/data/dem used by the accuracy tests (skipped when absent).
#pragma once

#include "geo/dem.h"
#include "src/terrain.h"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace demlight {

/// Path of a DEM in the shared data folder (DEMLIGHT_SHARED_DEM_DIR).
inline std::string sharedDemPath(const std::string& name) {
    return std::string(DEMLIGHT_SHARED_DEM_DIR) + "/" + name;
}

/// The terrain of a shared DEM, cropped to its centre cropW x cropH cells when both are > 0;
/// nullopt when the file is absent (the caller skips: GTEST_SKIP must be in the test body).
inline std::optional<Terrain> sharedTerrain(const std::string& name, std::size_t cropW = 0,
                                            std::size_t cropH = 0) {
    const std::string path = sharedDemPath(name);
    if (!std::filesystem::exists(path)) return std::nullopt;
    Terrain t = loadDem(path).terrain;
    if (cropW > 0 && cropH > 0) t = cropTerrainCentre(t, cropW, cropH);
    return t;
}

}  // namespace demlight
