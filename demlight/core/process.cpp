// Starting programs without a shell; see process.h.
#include "demlight/core/process.h"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace demlight {

std::optional<std::string> findProgram(const std::string& program) {
    if (program.empty()) return std::nullopt;
    const auto runnable = [](const std::string& p) {
        struct stat st {};
        return ::stat(p.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(p.c_str(), X_OK) == 0;
    };
    if (program.find('/') != std::string::npos) return runnable(program) ? std::optional(program) : std::nullopt;
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const std::string candidate = (std::filesystem::path(dir.empty() ? "." : dir) / program).string();
        if (runnable(candidate)) return candidate;
    }
    return std::nullopt;
}

ProgramExit runProgram(const ProgramCall& call) {
    ProgramExit result;
    if (call.argv.empty()) {
        result.why = "no program given";
        return result;
    }
    std::vector<char*> argv;
    for (const std::string& a : call.argv) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    const std::string log = call.logPath.empty() ? "/dev/null" : call.logPath;
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    if (!call.workingDir.empty()) posix_spawn_file_actions_addchdir_np(&actions, call.workingDir.c_str());

    // The child starts with the default action for the signals this process handles or ignores
    // (SIGXFSZ ignored here would hide a file size limit from it).
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults;
    sigemptyset(&defaults);
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGXFSZ, SIGPIPE}) sigaddset(&defaults, sig);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);

    pid_t pid = 0;
    const int err = posix_spawnp(&pid, argv[0], &actions, &attr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attr);
    if (err != 0) {
        result.why = "cannot start " + call.argv[0] + " (" + std::strerror(err) + ")";
        return result;
    }
    result.started = true;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            result.why = "lost " + call.argv[0] + " (" + std::strerror(errno) + ")";
            return result;
        }
    }
    if (WIFEXITED(status)) result.status = WEXITSTATUS(status);
    else if (WIFSIGNALED(status)) result.status = 128 + WTERMSIG(status);
    // posix_spawnp reports a program it could not exec as exit status 127 of the child.
    if (result.status != 0)
        result.why = call.argv[0] + (result.status == 127 ? " could not be run (exit status 127)"
                                                          : " failed (exit status " + std::to_string(result.status) + ")");
    return result;
}

double peakResidentBytes() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) * 1024.0;  // "VmHWM:  123 kB"
    return 0;
}

}  // namespace demlight
