// Signals and abnormal ends; see signals.h.
#include "demlight/geo/signals.h"

#include "demlight/geo/output_file.h"

#include <csignal>
#include <ctime>
#include <cstdlib>
#include <exception>

#include <signal.h>

namespace demlight {
namespace {

// Process-wide, as signal dispositions are: a handler can reach nothing but static storage.
// Both are set once, by installOutputCleanup, before any handler is installed.
StopRequest gOnFirstSignal = nullptr;
std::terminate_handler gDefaultTerminate = nullptr;
/// Whether a signal already asked the run to stop.
volatile std::sig_atomic_t gStopRequested = 0;

/// The first signal asks the work to stop (progress callbacks and writers between strips then
/// return false; the library throws Cancelled and its temporary files are removed as the stack
/// unwinds). A second ends the process at once, after unlinking the temporary files still
/// registered. Only async-signal-safe calls here.
void onSignal(int sig) {
    if (gStopRequested == 0) {
        gStopRequested = 1;
        if (gOnFirstSignal) gOnFirstSignal();
        return;
    }
    removeTemporaryFiles();
    // A writer thread may have claimed a temporary name and not yet created the file when the
    // names were unlinked (GDAL creates it just after): after a pause, unlink them all again.
    const timespec pause{0, 20'000'000};
    ::nanosleep(&pause, nullptr);
    removeTemporaryFiles();
    // The signal is blocked while its handler runs: with the default action restored it ends
    // the process as soon as this returns, with the status a shell expects from it.
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}

/// std::terminate ends the process without unwinding: remove the temporary files first, then
/// report as the runtime does.
[[noreturn]] void terminateRemovingTemporaries() {
    removeTemporaryFiles();
    if (gDefaultTerminate) gDefaultTerminate();
    std::abort();
}

}  // namespace

void installOutputCleanup(StopRequest onFirstSignal) {
    gOnFirstSignal = onFirstSignal;
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
        struct sigaction old {};
        if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
        struct sigaction sa {};
        sa.sa_handler = onSignal;
        sigemptyset(&sa.sa_mask);
        sa.sa_flags = SA_RESTART;  // restart reads and writes the signal interrupts
        sigaction(sig, &sa, nullptr);
    }
    ::signal(SIGXFSZ, SIG_IGN);
    gDefaultTerminate = std::set_terminate(terminateRemovingTemporaries);
    std::atexit(removeTemporaryFiles);
}

}  // namespace demlight
