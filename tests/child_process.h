// A demlight process for end-to-end tests that signal it: started with posix_spawn (its signal
// dispositions the default, so its own handlers are installed), stdout to /dev/null, stderr to a
// file.
#pragma once

#include <fcntl.h>
#include <filesystem>
#include <set>
#include <signal.h>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace demlight::testing {

class Child {
public:
    Child(const std::vector<std::string>& args, const std::filesystem::path& errPath) {
        std::vector<std::string> argv = {DEMLIGHT_CLI_PATH};
        argv.insert(argv.end(), args.begin(), args.end());
        std::vector<char*> cargv;
        for (auto& a : argv) cargv.push_back(a.data());
        cargv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        ok_ = posix_spawn(&pid_, cargv[0], &actions, nullptr, cargv.data(), environ) == 0;
        posix_spawn_file_actions_destroy(&actions);
    }
    ~Child() {
        if (ok_ && !done_) {
            ::kill(pid_, SIGKILL);
            wait();
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;
    bool started() const { return ok_; }
    pid_t pid() const { return pid_; }
    bool running() {
        if (done_) return false;
        if (::waitpid(pid_, &status_, WNOHANG) == pid_) done_ = true;
        return !done_;
    }
    void signal(int sig) { ::kill(pid_, sig); }
    int wait() {
        if (!done_) ::waitpid(pid_, &status_, 0);
        done_ = true;
        return status_;
    }

private:
    pid_t pid_ = -1;
    int status_ = 0;
    bool ok_ = false;
    bool done_ = false;
};

/// The folder's entries (paths relative to it), recursively. A child writing there makes and
/// removes its private temporary folder while this walks: a walk that meets an entry removed
/// under it starts again.
inline std::set<std::string> namesIn(const std::filesystem::path& dir) {
    for (int attempt = 0;; ++attempt) {
        try {
            std::set<std::string> names;
            for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
                names.insert(std::filesystem::relative(e.path(), dir).string());
            return names;
        } catch (const std::filesystem::filesystem_error&) {
            if (attempt == 100) throw;
        }
    }
}

}  // namespace demlight::testing
