// The real DEMs of ../shared/data/dem used by the accuracy tests (skipped when absent).
#pragma once

#include <string>

namespace demlight {

/// Path of a DEM in the shared data folder (DEMLIGHT_SHARED_DEM_DIR).
inline std::string sharedDemPath(const std::string& name) {
    return std::string(DEMLIGHT_SHARED_DEM_DIR) + "/" + name;
}

}  // namespace demlight
