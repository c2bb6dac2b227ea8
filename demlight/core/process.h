// Starting other programs (ffmpeg for MP4, gnuplot for the bench chart, GRASS as a peer) without
// a shell: each starts from an argument vector, so no file name, folder or other user string is
// ever read as a command.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace demlight {

/// One program to run and wait for.
struct ProgramCall {
    /// The program (looked up on PATH when it has no '/') and its arguments, passed as they are.
    std::vector<std::string> argv;
    /// The folder it runs in; empty: this process's.
    std::string workingDir;
    /// Where its standard output and error go (created or truncated); empty: /dev/null.
    std::string logPath;
};

/// The outcome of runProgram.
struct ProgramExit {
    bool started = false;  ///< false: it could not be started (`why` says why)
    int status = -1;       ///< its exit status, or 128 + the signal that ended it
    std::string why;
    bool ok() const { return started && status == 0; }
};

/// Runs `call` with posix_spawnp (no shell) and waits for it. Its standard input is /dev/null.
ProgramExit runProgram(const ProgramCall& call);

/// This process's peak resident set since its program started (bytes; Linux's VmHWM), or 0
/// where the system does not say. Unlike getrusage's, it leaves out what the process held
/// before its exec (a forked copy of its parent).
double peakResidentBytes();

/// The full path of `program` on PATH (an executable regular file), if any.
std::optional<std::string> findProgram(const std::string& program);

}  // namespace demlight
