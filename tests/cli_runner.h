// Runs the built demlight binary (DEMLIGHT_CLI_PATH) for end-to-end tests.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace demlight::testing {

struct RunResult {
    int exitCode = -1;
    std::string out;  ///< stdout
    std::string err;  ///< stderr
};

inline std::string readAll(std::FILE* f) {
    std::string s;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), f)) > 0) s.append(buf.data(), n);
    return s;
}

/// Runs `demlight ARGS` through the shell (ARGS is shell text); captures stdout and stderr.
/// `shellPrefix` runs first in the same shell, e.g. "ulimit -f 100; ". exitCode is -1 when the
/// process was ended by a signal.
inline RunResult runDemlight(const std::string& args, const std::string& shellPrefix = {}) {
    std::FILE* errFile = std::tmpfile();
    const std::string errPath = "/proc/self/fd/" + std::to_string(fileno(errFile));
    const std::string cmd = shellPrefix + "'" + DEMLIGHT_CLI_PATH + "' " + args + " 2>" + errPath;
    std::FILE* pipe = popen(cmd.c_str(), "r");
    RunResult r;
    if (!pipe) {
        std::fclose(errFile);
        r.err = "popen failed";
        return r;
    }
    r.out = readAll(pipe);
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::rewind(errFile);
    r.err = readAll(errFile);
    std::fclose(errFile);
    return r;
}

}  // namespace demlight::testing
