// The real DEMs of ../shared/data/dem used by the accuracy tests (skipped when absent).
#pragma once

#include "demlight/geo/dem.h"
#include "demlight/core/terrain.h"

#include <cctype>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace demlight {

/// Path of a DEM in the shared data folder (DEMLIGHT_SHARED_DEM_DIR).
inline std::string sharedDemPath(const std::string& name) {
    return std::string(DEMLIGHT_SHARED_DEM_DIR) + "/" + name;
}

/// A GoogleTest parameter name for a DEM file: its stem with every other character than a
/// letter or digit as '_' ("big_tujunga_srtm30m_utm11.tif" -> "big_tujunga_srtm30m_utm11").
inline std::string demTestName(const std::string& file) {
    std::string name = file.substr(0, file.find('.'));
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return name;
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
