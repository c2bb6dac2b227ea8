// demlight: light real terrain. Thin entry point: subcommands register themselves; every
// demlight::Error is caught here once and printed as one line.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "src/error.h"

#include <malloc.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>
#include <exception>
#include <iostream>

namespace {

/// SIGINT/SIGTERM: ask the work to stop at its next safe point (progress callbacks then return
/// false, the library throws Cancelled, main prints "cancelled" and returns 130). Only
/// async-signal-safe calls here. SA_RESETHAND has already restored the default action, so a
/// second signal ends the process at once.
void onInterrupt(int) {
    demlight::cli::requestCancel();
    static constexpr char kMessage[] = "\ndemlight: stopping at the next safe point (interrupt again to quit at once)\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

/// Installs onInterrupt for SIGINT and SIGTERM, except where the parent made the process ignore
/// the signal (nohup, background jobs of a non-interactive shell): that choice stands.
void installInterruptHandlers() {
    for (const int sig : {SIGINT, SIGTERM}) {
        struct sigaction old {};
        if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = onInterrupt;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESETHAND | SA_RESTART;  // restart reads and writes the signal interrupts
        sigaction(sig, &sa, nullptr);
    }
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
    app.fallthrough();  // subcommands inherit it: -q also works after the subcommand
    cli::registerInfo(app, ctx);
    cli::registerSunpos(app, ctx);
    cli::registerHorizon(app, ctx);
    cli::registerSun(app, ctx);
    cli::registerSky(app, ctx);
    cli::registerAperture(app, ctx);
    cli::registerLight(app, ctx);
    cli::registerRender(app, ctx);
    cli::registerTimelapse(app, ctx);
    cli::registerSunhours(app, ctx);
    cli::registerSequence(app, ctx);

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
    // An unknown first word is a mistyped command, not a missing one.
    if (!args.empty()) {
        const std::string& first = args.back();  // reversed
        std::string names;
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) {
            names += (names.empty() ? "" : ", ") + sub->get_name();
            known = known || sub->get_name() == first;
        }
        if (!first.empty() && first[0] != '-' && !known) {
            std::cerr << "demlight: error: unknown command '" << first << "' (commands: " << names << ")\n";
            return 109;
        }
    }

    installInterruptHandlers();
    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const Cancelled&) {
        std::cerr << "demlight: cancelled\n";
        return 130;
    } catch (const FieldError& e) {
        std::cerr << "demlight: error: " << cli::flagForField(e.field()) << e.detail() << "\n";
        return 1;
    } catch (const Error& e) {
        std::cerr << "demlight: error: " << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "demlight: internal error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
