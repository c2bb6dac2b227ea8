// The root command and the argument spellings it accepts (cli/commands.h).
#include "cli/commands.h"

#include <algorithm>

namespace demlight::cli {

namespace {
constexpr const char* kExitCodesHelp =
    "Exit codes: 0 done, 1 error (input, options, output), 2 bad command line, 3 internal error, "
    "130 cancelled (Ctrl-C, SIGTERM); a second Ctrl-C ends it at once, killed by SIGINT.";
}  // namespace

void registerCommands(CLI::App& app, CliContext& ctx) {
    app.description("demlight " DEMLIGHT_VERSION ": light real terrain from a georeferenced DEM");
    app.set_version_flag("--version", "demlight " DEMLIGHT_VERSION);
    app.add_flag("-q,--quiet", ctx.quiet, "No progress output");
    app.require_subcommand(1);
    app.footer(kExitCodesHelp);
    app.fallthrough();  // subcommands inherit it: -q also works after the subcommand
    registerInfo(app, ctx);
    registerSunpos(app, ctx);
    registerHorizon(app, ctx);
    registerSun(app, ctx);
    registerSky(app, ctx);
    registerAperture(app, ctx);
    registerLight(app, ctx);
    registerIrradiance(app, ctx);
    registerInsolation(app, ctx);
    registerRender(app, ctx);
    registerTimelapse(app, ctx);
    registerSunhours(app, ctx);
    registerSequence(app, ctx);
    registerOptions(app, ctx);
    for (CLI::App* sub : app.get_subcommands({})) sub->footer(kExitCodesHelp);

    // Argument errors in the same form as the others, naming the command's own help.
    app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
        std::string help = "demlight";
        if (failed && !failed->get_subcommands().empty()) help += " " + failed->get_subcommands().front()->get_name();
        return std::string("demlight: error: ") + e.what() + "\nRun '" + help + " --help' for the options.\n";
    });
}

std::vector<std::string> parserArguments(std::vector<std::string> args) {
    // GDAL spells these with one dash (-of COG, -co KEY=VALUE); accept both spellings.
    for (auto& a : args)
        if (a == "-of" || a == "-co") a = "-" + a;
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments reversed
    return args;
}

std::optional<std::string> unknownCommandMessage(const CLI::App& app, const std::vector<std::string>& reversedArgs) {
    // The global flags before the command (-q, --quiet) take no value, so the command is the
    // first argument that is not a flag.
    const auto word = std::find_if(reversedArgs.rbegin(), reversedArgs.rend(), [](const std::string& a) { return !a.starts_with('-'); });
    if (word == reversedArgs.rend() || word->empty()) return std::nullopt;
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) {
        if (sub->get_name() == *word) return std::nullopt;
        if (sub->get_group().empty()) continue;  // hidden (options --json)
        names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    return "demlight: error: unknown command '" + *word + "' (commands: " + names + ")";
}

}  // namespace demlight::cli
