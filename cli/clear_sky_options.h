// The clear-sky options of `irradiance` and `insolation`: --linke, --albedo, --coeff-bh,
// --coeff-dh, their rasters (--linke-raster, --albedo-raster, --coeff-bh-raster, --coeff-dh-raster),
// --diffuse-model, --solar-constant (demlight/products/irradiance.h).
#pragma once

#include "demlight/lighting/irradiance.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/sky.h"
#include "demlight/run/options.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace demlight::cli {

/// Adds the options; `monthOf` says whose month picks a monthly Linke value.
void addClearSkyOptions(CLI::App* cmd, ClearSkyOptions& o, const std::string& monthOf);

}  // namespace demlight::cli
