// A command's declaration (demlight/run/parameters.h) as CLI11 options: the command line's
// flags, checks, defaults and --help made from the one declaration.
#pragma once

#include "cli/commands.h"
#include "demlight/run/parameters.h"

#include <CLI/CLI.hpp>

namespace demlight::cli {

/// How this run's messages spell parameters: as flags, or as QGIS's form labels them when the
/// QGIS provider runs the command (DEMLIGHT_PARAMETER_NAMES=qgis).
Naming messageNaming();

/// Adds the subcommand `set.command()` to `app` with an option for each parameter of `set` the
/// command line shows, and records the declaration in `ctx` (options --json, error messages).
/// `set` must outlive `app`.
CLI::App* addDeclaredCommand(CLI::App& app, ParameterSet& set, CliContext& ctx);

}  // namespace demlight::cli
