// demlight: light real terrain. Thin entry point: subcommands register themselves; every
// demlight::Error is caught here once and printed as one line.
#include "cli/commands.h"
#include "cli/common.h"
#include "cli/declared.h"
#include "cli/progress_bar.h"
#include "demlight/geo/signals.h"
#include "demlight/core/error.h"

#include <malloc.h>
#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>
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
/// signal handler (demlight/geo/signals.h): async-signal-safe calls only.
void onFirstInterrupt() noexcept {
    demlight::cli::requestCancel();
    static constexpr char kMessage[] = "\ndemlight: stopping at the next safe point (interrupt again to quit at once)\n";
    [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
}

/// Set when SIGINT, SIGTERM or SIGHUP came before main() installed its handlers.
volatile std::sig_atomic_t gEarlySignal = 0;

void onEarlySignal(int sig) {
    if (gEarlySignal == 0) {
        gEarlySignal = sig;
        return;
    }
    // A second one ends the process at once, as later (nothing is written yet).
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

/// Runs before any library's initialisers (the executable's preinit array): installs a handler
/// that records a signal for main(), then releases the signals the launcher (cli/launcher.c) held
/// while this program loaded, so one that came meanwhile is delivered now, to that handler, and
/// main() ends with the documented status. Nothing is initialised yet: system calls and getenv
/// only.
void catchEarlySignals(int, char**, char** envp) {
    // (The environment from the arguments: getenv may not see it this early.)
    static constexpr char kHeld[] = "DEMLIGHT_SIGNALS_HELD=";
    const char* held = nullptr;
    for (char** e = envp; e && *e; ++e)
        if (std::strncmp(*e, kHeld, sizeof kHeld - 1) == 0) held = *e + sizeof kHeld - 1;
    sigset_t release;
    sigemptyset(&release);
    for (const auto& [sig, letter] : {std::pair{SIGINT, 'I'}, std::pair{SIGTERM, 'T'}, std::pair{SIGHUP, 'H'}}) {
        if (held && std::strchr(held, letter)) sigaddset(&release, sig);
        struct sigaction old {};
        if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;  // nohup stays
        struct sigaction sa {};
        sa.sa_handler = onEarlySignal;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;
        sigaction(sig, &sa, nullptr);
    }
    sigprocmask(SIG_UNBLOCK, &release, nullptr);
}

[[gnu::section(".preinit_array"), gnu::used]] void (*const kCatchEarlySignals)(int, char**, char**) = catchEarlySignals;

}  // namespace

int main(int argc, char** argv) {
    using namespace demlight;
    // First of all: the signal handlers, then a signal that came while the program loaded.
    installOutputCleanup(onFirstInterrupt);
    ::unsetenv("DEMLIGHT_SIGNALS_HELD");  // the launcher's word to this program alone
    if (gEarlySignal != 0) {
        std::cerr << "demlight: cancelled\n";
        return kExitCancelled;
    }
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

    try {
        app.parse(args);
    } catch (const CLI::ParseError& e) {
        // --help and --version end parsing too, successfully.
        return app.exit(e) == 0 ? kExitOk : kExitUsage;
    } catch (const Cancelled&) {
        std::cerr << "demlight: cancelled\n";
        return kExitCancelled;
    } catch (const Error& e) {
        std::cerr << "demlight: error: " << describeError(e, ctx.running, cli::messageNaming()) << "\n";
        return kExitError;
    } catch (const std::exception& e) {
        std::cerr << "demlight: internal error: " << e.what() << "\n";
        return kExitInternal;
    }
    return kExitOk;
}
