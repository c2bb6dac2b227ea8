// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the root app.
// Options are parsed into a struct; the callback calls the library and reports through
// CliContext. Errors are thrown as demlight::Error and caught once in main.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace demlight::cli {

/// Shared state of one invocation: the full command line (recorded in output metadata) and
/// whether to print progress.
struct CliContext {
    std::string commandLine;
    bool quiet = false;
};

void registerInfo(CLI::App& app, CliContext& ctx);
void registerSunpos(CLI::App& app, CliContext& ctx);
void registerHorizon(CLI::App& app, CliContext& ctx);
void registerSun(CLI::App& app, CliContext& ctx);
void registerSky(CLI::App& app, CliContext& ctx);
void registerAperture(CLI::App& app, CliContext& ctx);
void registerLight(CLI::App& app, CliContext& ctx);
void registerIrradiance(CLI::App& app, CliContext& ctx);
void registerInsolation(CLI::App& app, CliContext& ctx);
void registerRender(CLI::App& app, CliContext& ctx);
void registerTimelapse(CLI::App& app, CliContext& ctx);
void registerSunhours(CLI::App& app, CliContext& ctx);
void registerSequence(CLI::App& app, CliContext& ctx);

}  // namespace demlight::cli
