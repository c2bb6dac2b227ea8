// The root command and the argument spellings it accepts (cli/commands.h).
#include "cli/commands.h"

#include <algorithm>

namespace demlight::cli {

namespace {
constexpr const char* kExitCodesHelp =
    "Exit codes: 0 done, 1 error (input, options, output), 2 bad command line, 3 internal error, "
    "130 cancelled (Ctrl-C, SIGTERM); a second Ctrl-C ends it at once, killed by SIGINT.";

/// The value an option's usage shows: its type name without the validator CLI11 appends
/// ("DEG" of "DEG:[-90, 90]").
std::string valuePlaceholder(const CLI::Option& option) {
    const std::string type = option.get_type_name();
    return type.substr(0, type.find(':'));
}

/// Usage lines in the order a command is typed: the program and the command, the positional
/// arguments, the options a run cannot do without, then the rest
/// ("Usage: demlight sun DEM -o OUT.tif --time TIME [OPTIONS]"), all taken from the command's
/// own options so that the line cannot drift from them.
class UsageFormatter : public CLI::Formatter {
public:
    std::string make_usage(const CLI::App* app, std::string name) const override {
        std::string usage = "Usage: " + name;
        const bool hasOptional =
            !app->get_options([](const CLI::Option* o) { return o->nonpositional() && !o->get_required(); }).empty();
        if (!app->get_subcommands({}).empty()) return usage + (hasOptional ? " [OPTIONS]" : "") + " COMMAND\n";
        for (const CLI::Option* p : app->get_options([](const CLI::Option* o) { return o->get_positional(); }))
            usage += " " + (p->get_required() ? p->get_name() : "[" + p->get_name() + "]");
        for (const CLI::Option* o :
             app->get_options([](const CLI::Option* o) { return o->nonpositional() && o->get_required(); })) {
            const std::string flag = o->get_snames().empty() ? "--" + o->get_lnames().front() : "-" + o->get_snames().front();
            usage += " " + flag + " " + valuePlaceholder(*o);
        }
        return usage + (hasOptional ? " [OPTIONS]" : "") + "\n";
    }
};

/// The arguments no option took, in the order they were typed (CLI11's own ExtrasError message
/// lists them reversed, having been handed the reversed command line of parserArguments).
std::string extrasMessage(const CLI::App& app) {
    const std::vector<std::string> extras = app.remaining(/*recurse=*/true);
    std::string m = extras.size() > 1 ? "The following arguments were not expected:" : "The following argument was not expected:";
    for (const std::string& a : extras) m += " " + a;
    return m;
}
}  // namespace

void registerCommands(CLI::App& app, CliContext& ctx) {
    app.name("demlight");  // usage lines name the program: "Usage: demlight sun DEM ..."
    app.formatter(std::make_shared<UsageFormatter>());  // subcommands added below inherit it
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
    registerView(app, ctx);
    registerTimelapse(app, ctx);
    registerSunhours(app, ctx);
    registerSequence(app, ctx);
    registerBench(app, ctx);
    registerQuicklook(app, ctx);
    registerOptions(app, ctx);
    for (CLI::App* sub : app.get_subcommands({})) sub->footer(kExitCodesHelp);

    // Argument errors in the same form as the others, naming the command's own help.
    app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
        std::string help = "demlight";
        if (failed && !failed->get_subcommands().empty()) help += " " + failed->get_subcommands().front()->get_name();
        const bool extras = failed && dynamic_cast<const CLI::ExtrasError*>(&e) != nullptr;
        return std::string("demlight: error: ") + (extras ? extrasMessage(*failed) : std::string(e.what())) + "\nRun '" +
               help + " --help' for the options.\n";
    });
}

std::vector<std::string> parserArguments(std::vector<std::string> args) {
    // GDAL spells these with one dash (-of COG, -co KEY=VALUE, -ot Int16); accept both spellings.
    for (auto& a : args)
        if (a == "-of" || a == "-co" || a == "-ot") a = "-" + a;
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
