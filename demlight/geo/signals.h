// How a program that writes outputs ends (docs/design.md §8): by a signal, by std::terminate
// or by exit() from inside a library, it leaves no temporary file behind (demlight/geo/output_file.h).
// Process-wide by nature (signal dispositions are), so a program calls it once, from main.
#pragma once

namespace demlight {

/// Called from the signal handler on the first SIGINT, SIGTERM or SIGHUP: it must only make
/// async-signal-safe calls (store an atomic, write(2)). It should ask the work to stop at its next
/// safe point (a progress callback returning false), which the library reports as Cancelled.
using StopRequest = void (*)() noexcept;

/// Installs, for the rest of the process:
///  - SIGINT, SIGTERM, SIGHUP: the first calls `onFirstSignal`; a second unlinks the temporary
///    files still registered (removeTemporaryFiles) and ends the process by that signal, as a
///    shell expects. A signal the parent made the process ignore (nohup, background jobs of a
///    non-interactive shell) stays ignored.
///  - SIGXFSZ ignored: a write past the file size limit (ulimit -f) then fails with EFBIG and is
///    reported like a full disk, instead of ending the process with its temporary files left.
///  - std::terminate (an exception escaping a thread) and exit() (libjpeg's default error handler
///    calls it on a full disk) remove the temporary files first.
void installOutputCleanup(StopRequest onFirstSignal);

}  // namespace demlight
