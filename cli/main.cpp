// demlight: light real terrain. Thin entry point: subcommands register themselves; every
// demlight::Error is caught here once and printed as one line.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/progress_bar.h"
#include "geo/signals.h"
#include "src/error.h"

#include <malloc.h>
#include <unistd.h>

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

/// The first Ctrl-C (SIGTERM, SIGHUP): stop at the next safe point, and say so. Runs in the
/// signal handler (geo/signals.h): async-signal-safe calls only.
void onFirstInterrupt() noexcept {
    demlight::cli::requestCancel();
    static constexpr char kMessage[] = "\ndemlight: stopping at the next safe point (interrupt again to quit at once)\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
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

    CLI::App app;
    cli::registerCommands(app, ctx);
    std::vector<std::string> args = cli::parserArguments({argv + 1, argv + argc});
    if (const auto unknown = cli::unknownCommandMessage(app, args)) {
        std::cerr << *unknown << "\n";
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
