// demlight: light real terrain. Thin entry point: subcommands register themselves; every
// demlight::Error is caught here once and printed as one line.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/signals.h"
#include "src/error.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>
#include <exception>
#include <iostream>

namespace {

/// Exit codes of every command (docs/commands.md "Exit codes"; also in --help).
enum ExitCode : int {
    kExitOk = 0,
    kExitError = 1,         ///< a demlight::Error: bad input, option value, output path, full disk, ...
    kExitUsage = 2,         ///< the command line does not parse (unknown command or option, missing value)
    kExitInternal = 3,      ///< a bug: any other exception
    kExitCancelled = 130,   ///< stopped by SIGINT (Ctrl-C), SIGTERM or SIGHUP at a safe point (128 + SIGINT)
};
constexpr const char* kExitCodesHelp =
    "Exit codes: 0 done, 1 error (input, options, output), 2 bad command line, 3 internal error, "
    "130 cancelled (Ctrl-C, SIGTERM); a second Ctrl-C ends it at once, killed by SIGINT.";

/// The first Ctrl-C (SIGTERM, SIGHUP): stop at the next safe point, and say so. Runs in the
/// signal handler (geo/signals.h): async-signal-safe calls only.
void onFirstInterrupt() noexcept {
    demlight::cli::requestCancel();
    static constexpr char kMessage[] = "\ndemlight: stopping at the next safe point (interrupt again to quit at once)\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

/// An unknown first word is a mistyped command, not a missing one: its message, or empty. The
/// global flags before it (-q, --quiet) take no value, so it is the first argument that is not a
/// flag. `reversed` is the command line as CLI11 takes it.
std::string unknownCommand(const CLI::App& app, const std::vector<std::string>& reversed) {
    const auto word = std::find_if(reversed.rbegin(), reversed.rend(), [](const std::string& a) { return !a.starts_with('-'); });
    if (word == reversed.rend() || word->empty()) return {};
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) {
        if (sub->get_name() == *word) return {};
        names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    return "unknown command '" + *word + "' (commands: " + names + ")";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace demlight;
    // Grids of tens of MB are allocated and freed per frame (time-lapses, sun hours). glibc maps
    // each one afresh from the kernel (zeroed, one fault per 4 KiB page); keep freed memory in
    // the heap for reuse instead, which cuts the kernel time of frame loops
    // (docs/measurements.md#climaincpp-main-mallopt).
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
    cli::CliContext ctx;
    for (int i = 0; i < argc; ++i) {
        if (i) ctx.commandLine += ' ';
        ctx.commandLine += argv[i];
    }

    CLI::App app{"demlight " DEMLIGHT_VERSION ": light real terrain from a georeferenced DEM"};
    app.set_version_flag("--version", "demlight " DEMLIGHT_VERSION);
    app.add_flag("-q,--quiet", ctx.quiet, "No progress output");
    app.require_subcommand(1);
    app.footer(kExitCodesHelp);
    app.fallthrough();  // subcommands inherit it: -q also works after the subcommand
    cli::registerInfo(app, ctx);
    cli::registerSunpos(app, ctx);
    cli::registerHorizon(app, ctx);
    cli::registerSun(app, ctx);
    cli::registerSky(app, ctx);
    cli::registerAperture(app, ctx);
    cli::registerLight(app, ctx);
    cli::registerIrradiance(app, ctx);
    cli::registerInsolation(app, ctx);
    cli::registerRender(app, ctx);
    cli::registerTimelapse(app, ctx);
    cli::registerSunhours(app, ctx);
    cli::registerSequence(app, ctx);
    for (CLI::App* sub : app.get_subcommands({})) sub->footer(kExitCodesHelp);

    // GDAL spells these with one dash (-of COG, -co KEY=VALUE); accept both spellings.
    std::vector<std::string> args(argv + 1, argv + argc);
    for (auto& a : args)
        if (a == "-of" || a == "-co") a = "-" + a;
    std::reverse(args.begin(), args.end());  // CLI11 takes the arguments reversed

    // Argument errors in the same form as the others, naming the command's own help.
    app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
        std::string help = "demlight";
        if (failed && !failed->get_subcommands().empty()) help += " " + failed->get_subcommands().front()->get_name();
        return std::string("demlight: error: ") + e.what() + "\nRun '" + help + " --help' for the options.\n";
    });
    if (const std::string unknown = unknownCommand(app, args); !unknown.empty()) {
        std::cerr << "demlight: error: " << unknown << "\n";
        return kExitUsage;
    }

    installOutputCleanup(onFirstInterrupt);
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        // --help and --version end parsing too, successfully.
        return app.exit(e) == 0 ? kExitOk : kExitUsage;
    } catch (const Cancelled&) {
        std::cerr << "demlight: cancelled\n";
        return kExitCancelled;
    } catch (const FieldError& e) {
        std::cerr << "demlight: error: " << cli::flagForField(e.field()) << e.detail() << "\n";
        return kExitError;
    } catch (const Error& e) {
        std::cerr << "demlight: error: " << e.what() << "\n";
        return kExitError;
    } catch (const std::exception& e) {
        std::cerr << "demlight: internal error: " << e.what() << "\n";
        return kExitInternal;
    }
    return kExitOk;
}
