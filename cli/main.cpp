// demlight: light real terrain. Thin entry point: subcommands register themselves; every
// demlight::Error is caught here once and printed as one line.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/output_file.h"
#include "src/error.h"

#include <malloc.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>
#include <exception>
#include <iostream>

namespace {

/// Exit codes of every command (README "Exit codes"; also in --help).
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

/// Whether a signal already asked the run to stop.
volatile std::sig_atomic_t gStopRequested = 0;

/// SIGINT/SIGTERM/SIGHUP. The first asks the work to stop at its next safe point (progress
/// callbacks, writers between strips, then return false; the library throws Cancelled, its
/// temporary files are removed as the stack unwinds, main prints "cancelled"). A second ends the
/// process at once, after unlinking the temporary files still registered (geo/output_file.h).
/// Only async-signal-safe calls here.
void onInterrupt(int sig) {
    if (gStopRequested == 0) {
        gStopRequested = 1;
        demlight::cli::requestCancel();
        static constexpr char kMessage[] = "\ndemlight: stopping at the next safe point (interrupt again to quit at once)\n";
        [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
        return;
    }
    demlight::removeTemporaryFiles();
    // The signal is blocked while its handler runs: with the default action restored it ends
    // the process as soon as this returns, with the status a shell expects from it.
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

/// Installs onInterrupt, except where the parent made the process ignore the signal (nohup,
/// background jobs of a non-interactive shell): that choice stands. SIGXFSZ (a write past the
/// file size limit, ulimit -f) would end the process with its temporary files left; ignored,
/// that write fails with EFBIG and is reported like a full disk.
void installSignalHandlers() {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction old {};
        if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = onInterrupt;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;  // restart reads and writes the signal interrupts
        sigaction(sig, &sa, nullptr);
    }
    ::signal(SIGXFSZ, SIG_IGN);
}

std::terminate_handler gDefaultTerminate = nullptr;

/// std::terminate (an exception escaping a thread) ends the process without unwinding: remove
/// the temporary files first, then report as the runtime does.
[[noreturn]] void terminateRemovingTemporaries() {
    demlight::removeTemporaryFiles();
    if (gDefaultTerminate) gDefaultTerminate();
    std::abort();
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
    // An unknown first word is a mistyped command, not a missing one. The global flags before
    // it (-q, --quiet) take no value, so it is the first argument that is not a flag.
    const auto word = std::find_if(args.rbegin(), args.rend(), [](const std::string& a) { return !a.starts_with('-'); });
    if (word != args.rend()) {
        const std::string& first = *word;  // args are reversed
        std::string names;
        bool known = false;
        for (const CLI::App* sub : app.get_subcommands({})) {
            names += (names.empty() ? "" : ", ") + sub->get_name();
            known = known || sub->get_name() == first;
        }
        if (!first.empty() && first[0] != '-' && !known) {
            std::cerr << "demlight: error: unknown command '" << first << "' (commands: " << names << ")\n";
            return kExitUsage;
        }
    }

    installSignalHandlers();
    gDefaultTerminate = std::set_terminate(terminateRemovingTemporaries);
    // A library that calls exit() on a write error (libjpeg's default handler does, on a full
    // disk) skips the unwinding that removes temporary files.
    std::atexit(demlight::removeTemporaryFiles);
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
