// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the root app.
// Options are parsed into a struct; the callback calls the library and reports through
// CliContext. Errors are thrown as demlight::Error and caught once in main.
#pragma once

#include "demlight/run/parameters.h"
#include "demlight/run/runner.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace demlight::cli {


/// What a command writes, where -o is not simply one GDAL raster.
struct CommandOutputs {
    /// What -o names: "folder", "picture"; empty: a GDAL raster (-o with --of) or a file.
    std::string kind;
    /// Metadata items of the -o raster that name further rasters written with it.
    std::vector<std::string> companionKeys;
};

/// Shared state of one invocation: the full command line (recorded in output metadata) and
/// whether to print progress.
struct CliContext {
    std::string commandLine;
    bool quiet = false;
    /// Each command's declaration (cli/declared.h), by name: options --json and messages.
    std::map<std::string, const ParameterSet*> declarations;
    /// The declaration of the command being run, once its arguments are parsed: the messages
    /// of its errors spell its parameters (describeError).
    const ParameterSet* running = nullptr;
    /// What commands write beyond one GDAL raster at -o, by command name, for programs that drive
    /// demlight (options --json, cli/cmd_options.cpp).
    std::map<std::string, CommandOutputs> outputs;
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
void registerView(CLI::App& app, CliContext& ctx);
void registerQuicklook(CLI::App& app, CliContext& ctx);
void registerTimelapse(CLI::App& app, CliContext& ctx);
void registerSunhours(CLI::App& app, CliContext& ctx);
void registerSequence(CLI::App& app, CliContext& ctx);
void registerBench(CLI::App& app, CliContext& ctx);
/// The hidden `options --json` command: every other command's options as JSON.
void registerOptions(CLI::App& app, CliContext& ctx);
/// What `demlight options --json` prints: every listed command of `app` (built by registerCommands
/// with `ctx`) with its options, defaults and help, as JSON text (docs/commands.md).
std::string optionsJson(const CLI::App& app, const CliContext& ctx);

/// Makes `app` demlight's root command: --version, -q, every command above, and argument errors
/// in demlight's one-line form (cli/command_line.cpp). main() parses with it, and so does the
/// command-line fuzzer (fuzz/cli_args_fuzz.cpp) with the commands' callbacks replaced.
void registerCommands(CLI::App& app, CliContext& ctx);

/// The arguments (argv without the program name) as the root command parses them: GDAL's
/// one-dash -of and -co accepted as --of and --co, and reversed, as CLI11 takes them.
std::vector<std::string> parserArguments(std::vector<std::string> args);

/// The error for a first word that names no command (a mistyped command, not a missing one);
/// nothing when the first word is a command or an option.
std::optional<std::string> unknownCommandMessage(const CLI::App& app, const std::vector<std::string>& reversedArgs);

}  // namespace demlight::cli
