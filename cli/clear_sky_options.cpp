#include "cli/clear_sky_options.h"

#include "cli/common.h"
#include "demlight/core/error.h"

#include <cmath>
#include <sstream>

namespace demlight::cli {

void addClearSkyOptions(CLI::App* cmd, ClearSkyOptions& o, const std::string& monthOf) {
    auto* linke = cmd->add_option("--linke", o.linke,
                    "Linke turbidity factor (air mass 2, 1-10): one value, or 12 comma-separated monthly values "
                    "(January first) of which the month of " + monthOf + " is used")
        ->capture_default_str();
    auto* albedo = cmd->add_option("--albedo", o.albedo, "Ground albedo of the reflected component (0-1)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    auto* coeffBh = cmd->add_option("--coeff-bh", o.coeffBh,
                    "Real-sky beam index: fraction of the clear-sky beam that reaches the ground (0-1, r.sun coeff_bh)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    auto* coeffDh = cmd->add_option("--coeff-dh", o.coeffDh,
                    "Real-sky diffuse index: fraction of the clear-sky diffuse that reaches the ground (0-1, r.sun "
                    "coeff_dh)")
        ->check(finiteRange(0.0, 1.0))
        ->capture_default_str();
    // r.sun's linke, albedo, coeff_bh and coeff_dh maps: one raster each, resampled bilinearly.
    const std::string resampled = " (band 1, any raster GDAL opens; resampled bilinearly onto the DEM's grid; "
                                  "nodata where it has none)";
    cmd->add_option("--linke-raster", o.linkeRaster,
                    "Linke turbidity per cell, 1-10, instead of --linke: a raster of one band, or of 12 monthly bands "
                    "(band m = month m, January first) of which the month of " + monthOf +
                        " is used; or the option given 12 times, one one-band raster per month, January first (any "
                        "raster GDAL opens; resampled bilinearly onto the DEM's grid; nodata where it has none)")
        ->excludes(linke)
        ->type_name("PATH");
    cmd->add_option("--albedo-raster", o.albedoRaster, "Ground albedo per cell, 0-1, instead of --albedo" + resampled)
        ->excludes(albedo)
        ->type_name("PATH");
    cmd->add_option("--coeff-bh-raster", o.coeffBhRaster, "Real-sky beam index per cell, 0-1, instead of --coeff-bh" + resampled)
        ->excludes(coeffBh)
        ->type_name("PATH");
    cmd->add_option("--coeff-dh-raster", o.coeffDhRaster,
                    "Real-sky diffuse index per cell, 0-1, instead of --coeff-dh" + resampled)
        ->excludes(coeffDh)
        ->type_name("PATH");
    cmd->add_option("--diffuse-model", o.diffuseModel,
                    "visible-sky: diffuse horizontal x the sky the horizons leave above the horizontal, reflected "
                    "from the rest of the view; rsun: r.sun's Muneer tilted-surface diffuse and (1 - cos slope)/2 "
                    "reflected")
        ->check(CLI::IsMember({"visible-sky", "rsun"}))
        ->capture_default_str();
    cmd->add_option("--solar-constant", o.solarConstantWm2,
                    "Solar constant (W/m2); the extraterrestrial irradiance is this / R^2 at the sun-earth distance R")
        ->check(finiteRange(1000, 1500))
        ->capture_default_str();
}

}  // namespace demlight::cli
