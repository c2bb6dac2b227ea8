// The clear-sky options of `irradiance` and `insolation`: --linke, --albedo, --coeff-bh,
// --coeff-dh, --diffuse-model, --solar-constant (products/irradiance.h).
#pragma once

#include "lighting/irradiance.h"
#include "products/sky.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace demlight::cli {

struct ClearSkyOptions {
    std::string linke = formatNumber(kDefaultLinke);
    double albedo = kDefaultAlbedo;
    double coeffBh = 1, coeffDh = 1;
    std::string diffuseModel = "visible-sky";
    double solarConstantWm2 = kSolarConstantWm2;
};
/// Adds the options; `monthOf` says whose month picks a monthly Linke value.
void addClearSkyOptions(CLI::App* cmd, ClearSkyOptions& o, const std::string& monthOf);

/// --linke: "3.2" or 12 comma-separated numbers (the product checks the count and range).
std::vector<double> parseLinkeOption(const std::string& text);

}  // namespace demlight::cli
