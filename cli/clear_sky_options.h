// The clear-sky options of `irradiance` and `insolation`: --linke, --albedo, --coeff-bh,
// --coeff-dh, their rasters (--linke-raster, --albedo-raster, --coeff-bh-raster, --coeff-dh-raster),
// --diffuse-model, --solar-constant (demlight/products/irradiance.h).
#pragma once

#include "demlight/lighting/irradiance.h"
#include "demlight/products/irradiance.h"
#include "demlight/products/sky.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace demlight::cli {

struct ClearSkyOptions {
    std::string linke = formatNumber(kDefaultLinke);
    double albedo = kDefaultAlbedo;
    double coeffBh = 1, coeffDh = 1;
    std::vector<std::string> linkeRaster;  ///< one path, or twelve (one per use)
    std::string albedoRaster, coeffBhRaster, coeffDhRaster;
    std::string diffuseModel = "visible-sky";
    double solarConstantWm2 = kSolarConstantWm2;
};
/// Adds the options; `monthOf` says whose month picks a monthly Linke value.
void addClearSkyOptions(CLI::App* cmd, ClearSkyOptions& o, const std::string& monthOf);

/// The --*-raster options as the requests take them.
ClearSkyRasters clearSkyRasters(const ClearSkyOptions& o);

/// --linke: "3.2" or 12 comma-separated numbers (the product checks the count and range).
std::vector<double> parseLinkeOption(const std::string& text);

}  // namespace demlight::cli
