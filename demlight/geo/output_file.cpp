// Output files; see output_file.h.
#include "demlight/geo/output_file.h"

#include "demlight/core/error.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <limits>
#include <mutex>
#include <set>
#include <vector>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace demlight {
namespace {

namespace fs = std::filesystem;

/// Live temporary files at once: the time-lapse has at most a few in flight (a frame's TIFF and
/// PNG, the GIF, the index); a writer that finds the table full still works, it only loses the
/// clean-up on a second Ctrl-C.
constexpr std::size_t kMaxTemporaries = 64;
/// Longest temporary path the table holds (PATH_MAX on Linux).
constexpr std::size_t kMaxTemporaryPath = 4096;
/// What diagnoseWriteFailure tries to append: more than a file system's block, so a file whose
/// last block still has room does not hide a full disk.
constexpr off_t kProbeBytes = 64 * 1024;

enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2, kRemoving = 3 };

/// One private folder of a temporary file. The state moves kFree -> kFilling (a writer claims it
/// and makes the folder) -> kLive -> kFree (committed or removed), or kLive -> kRemoving
/// (removeTemporaryFiles).
struct Slot {
    std::atomic<int> state{kFree};
    char path[kMaxTemporaryPath];
};
static_assert(std::atomic<int>::is_always_lock_free);

// The one piece of process-wide mutable state in the library, and why: a signal handler that
// ends the process at once can reach nothing else (no locks, no allocation), so the paths to
// remove must already sit in static storage.
Slot gSlots[kMaxTemporaries];

/// Claims a slot and makes the private folder from `templ` (ending in "XXXXXX") inside it, so
/// that the folder is in the table from the moment it exists. Returns the slot, or -1 with
/// `folder` made all the same when the table is full or the path too long; throws Error when
/// mkdtemp fails.
int makePrivateFolder(const std::string& templ, std::string& folder) {
    const auto make = [&](char* buffer) {
        if (::mkdtemp(buffer) == nullptr) {
            const int err = errno;
            throw Error("cannot write in folder '" + fs::path(templ).parent_path().string() + "': " + std::strerror(err));
        }
        folder = buffer;
    };
    if (templ.size() < kMaxTemporaryPath) {
        for (std::size_t i = 0; i < kMaxTemporaries; ++i) {
            int expected = kFree;
            if (!gSlots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acquire)) continue;
            std::memcpy(gSlots[i].path, templ.c_str(), templ.size() + 1);
            try {
                make(gSlots[i].path);
            } catch (...) {
                gSlots[i].state.store(kFree, std::memory_order_release);
                throw;
            }
            gSlots[i].state.store(kLive, std::memory_order_release);
            return static_cast<int>(i);
        }
    }
    std::vector<char> buffer(templ.begin(), templ.end());
    buffer.push_back('\0');
    make(buffer.data());
    return -1;
}

/// Removes `folder` and the files directly in it (a private folder holds no subfolders) without
/// following any link: async-signal-safe system calls only.
void removeFolderSignalSafe(const char* folder) noexcept {
    const int fd = ::open(folder, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd >= 0) {
        alignas(8) char buffer[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, fd, buffer, sizeof buffer);
            if (n <= 0) break;
            for (long at = 0; at < n;) {
                // struct linux_dirent64: d_ino (8), d_off (8), d_reclen (2), d_type (1), d_name.
                unsigned short reclen;
                std::memcpy(&reclen, buffer + at + 16, sizeof reclen);
                const char* name = buffer + at + 19;
                if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0) ::unlinkat(fd, name, 0);
                at += reclen;
            }
        }
        ::close(fd);
    }
    ::rmdir(folder);
}

/// Whether process `pid` still runs (or runs as another user).
bool processRuns(long pid) {
    if (pid <= 0 || pid > std::numeric_limits<pid_t>::max()) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

/// The pid in a temporary name's ".tmp<pid>" or ".tmp<pid>-XXXXXX" tail, or -1.
long pidOfTemporary(const std::string& name) {
    const auto tmp = name.rfind(".tmp");
    if (tmp == std::string::npos) return -1;
    std::size_t end = name.size();
    if (const auto dash = name.find('-', tmp); dash != std::string::npos) {
        if (name.size() - dash - 1 != 6) return -1;
        end = dash;
    }
    const std::string digits = name.substr(tmp + 4, end - tmp - 4);
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
        return -1;
    return std::stol(digits);
}

/// Removes what a temporary name in `dir` left when its process no longer runs: a private folder
/// and its files, or an earlier version's temporary file. Only this user's; links are removed,
/// never followed.
void removeStaleTemporary(const fs::path& entry) {
    struct stat st {};
    if (::lstat(entry.c_str(), &st) != 0 || st.st_uid != ::geteuid()) return;
    if (processRuns(pidOfTemporary(entry.filename().string()))) return;
    std::error_code ec;
    fs::remove_all(entry, ec);  // does not follow links
}

void releaseSlot(int slot) {
    if (slot < 0) return;
    int expected = kLive;
    // A slot in kRemoving belongs to removeTemporaryFiles, which runs only as the process ends.
    gSlots[slot].state.compare_exchange_strong(expected, kFree, std::memory_order_release);
}

std::string nodeKind(const fs::file_status& s) {
    switch (s.type()) {
    case fs::file_type::character: return "a character device";
    case fs::file_type::block: return "a block device";
    case fs::file_type::fifo: return "a fifo (named pipe)";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
    }
}

std::string describeErrno(int err) {
    switch (err) {
    case 0: return {};
    case ENOSPC: return "the disk is full (" + std::string(std::strerror(err)) + ")";
    case EDQUOT: return "the disk quota is used up (" + std::string(std::strerror(err)) + ")";
    case EFBIG:
        return "file too large for the file size limit (ulimit -f) or for the file system (" +
               std::string(std::strerror(err)) + ")";
    default: return std::strerror(err);
    }
}

/// Appends up to kProbeBytes of zeros at the end of `fd`, then restores its size; the errno of
/// the first failed write, or 0.
int probeAppend(int fd) {
    struct stat st {};
    if (::fstat(fd, &st) != 0) return 0;
    static const char zeros[4096] = {};
    int err = 0;
    off_t written = 0;
    while (written < kProbeBytes) {
        const ssize_t n = ::pwrite(fd, zeros, sizeof zeros, st.st_size + written);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : 0;
            break;
        }
        written += n;
    }
    [[maybe_unused]] const int truncated = ::ftruncate(fd, st.st_size);
    return err;
}

/// Removes, the first time this process writes into `folder`, the private folders that processes
/// no longer running left there (SIGKILL leaves them): directories named ".NAME.tmp<pid>-XXXXXX"
/// and owned by this user. Files of other names, other users' and live processes' are left.
void removeStaleFoldersOnce(const fs::path& folder) {
    static std::mutex mutex;
    static std::set<std::string> scanned;
    {
        std::lock_guard lock(mutex);
        if (!scanned.insert(folder.string()).second) return;
    }
    std::error_code ec;
    std::vector<fs::path> stale;
    for (const auto& e : fs::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        if (name.starts_with('.') && name.find('-', name.rfind(".tmp")) != std::string::npos && isTemporaryName(name) &&
            e.is_directory(ec) && !e.is_symlink(ec))
            stale.push_back(e.path());
    }
    for (const auto& p : stale) removeStaleTemporary(p);
}

}  // namespace

void checkNotInput(const std::string& path, const std::string& inputPath) {
    std::error_code ec;
    if (!inputPath.empty() && fs::exists(path, ec) && fs::equivalent(fs::path(path), fs::path(inputPath), ec))
        throw ParameterError("{output} '" + path + "' would overwrite its input; choose another {output}");
}

void checkOutputFile(const std::string& path) {
    if (path.empty()) throw Error("cannot write '': the output path is empty");
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // follows symbolic links
    if (fs::is_directory(status)) throw Error("cannot write '" + path + "': it is a directory");
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw Error("'" + path + "' is " + nodeKind(status) +
                    ", not a regular file; demlight writes files (a temporary file renamed into place), "
                    "which would replace it: choose a file path");
    const fs::path parent = fs::absolute(fs::path(path), ec).parent_path();
    if (ec || !fs::is_directory(parent, ec))
        throw Error("cannot write '" + path + "': folder '" + parent.string() + "' does not exist");
}

void checkOutputFolder(const std::string& dir, bool replaceEarlier) {
    if (dir.empty()) throw Error("cannot write '': the output folder path is empty");
    std::error_code ec;
    const fs::file_status status = fs::status(dir, ec);
    if (!fs::exists(status)) return;
    if (!fs::is_directory(status))
        throw Error("'" + dir + "' is not a folder: give a new or an empty folder for the outputs");
    if (replaceEarlier) return;
    std::size_t entries = 0;
    std::string example;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (entries++ == 0) example = e.path().filename().string();
    if (entries > 0)
        throw FieldError("overwrite", " not given, and the folder '" + dir + "' is not empty (" + std::to_string(entries) +
                                          (entries == 1 ? " entry" : " entries") + ", e.g. '" + example +
                                          "'): the files of two runs would mix; give it to replace an earlier run's "
                                          "files there, or choose a new folder");
}

bool isTemporaryName(const std::string& name, std::string* finalName) {
    if (pidOfTemporary(name) < 0) return false;
    if (finalName) {
        *finalName = name.substr(0, name.rfind(".tmp"));
        if (finalName->starts_with('.')) finalName->erase(0, 1);
    }
    return true;
}

void removeEarlierOutputs(const std::string& dir, const std::function<bool(const std::string& name)>& isEarlierOutput) {
    std::error_code ec;
    std::vector<fs::path> earlier, stale;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        const std::string name = e.path().filename().string();
        std::string finalName;
        if (isTemporaryName(name, &finalName)) {
            if (isEarlierOutput(finalName)) stale.push_back(e.path());
        } else if (e.is_regular_file(ec) && !e.is_symlink(ec) && isEarlierOutput(name)) {
            earlier.push_back(e.path());
        }
    }
    for (const auto& p : stale) removeStaleTemporary(p);
    for (const auto& p : earlier)
        if (!fs::remove(p, ec) && ec) throw Error("cannot remove '" + p.string() + "' of an earlier run (" + ec.message() + ")");
}

FolderLock::FolderLock(const std::string& dir) {
    fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd_ < 0) {
        const int err = errno;
        throw Error("cannot write into folder '" + dir + "': " + std::strerror(err));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int err = errno;
        ::close(fd_);
        fd_ = -1;
        throw Error(err == EWOULDBLOCK ? "folder '" + dir + "' is being written by another demlight run; wait for it to "
                                                            "end or choose another folder"
                                       : "cannot lock folder '" + dir + "': " + std::strerror(err));
    }
}

FolderLock::~FolderLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
}

void checkFolderAcceptsFiles(const std::string& folder, const std::string& forOutput) {
    std::string made;
    try {
        const int slot = makePrivateFolder((fs::path(folder) / (".demlight-probe.tmp" + std::to_string(::getpid()) + "-XXXXXX")).string(), made);
        ::rmdir(made.c_str());
        releaseSlot(slot);
    } catch (const Error&) {
        throw Error("cannot write '" + forOutput + "': folder '" + folder + "' is not writable");
    }
}

std::string diagnoseWriteFailure(const std::string& path) {
    int fd = ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_CLOEXEC);
    std::string probe;
    if (fd < 0) {
        std::error_code ec;
        probe = (fs::absolute(fs::path(path), ec).parent_path() / (".demlight-probe-" + std::to_string(::getpid())))
                    .string();
        fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd < 0) return errno == ENOSPC || errno == EDQUOT ? describeErrno(errno) : std::string();
    }
    const int err = probeAppend(fd);
    ::close(fd);
    if (!probe.empty()) ::unlink(probe.c_str());
    return describeErrno(err);
}

std::string writeFailureMessage(const std::string& subject, const std::string& writtenPath,
                                const std::string& reason) {
    std::string message = "cannot write " + subject;
    const std::string diagnosis = diagnoseWriteFailure(writtenPath);
    if (!diagnosis.empty()) message += ": " + diagnosis;
    if (!reason.empty()) message += " (" + reason + ")";
    return message;
}

TemporaryFile::TemporaryFile(const std::string& finalPath) : finalPath_(finalPath) {
    std::error_code ec;
    const fs::path p = fs::absolute(fs::path(finalPath), ec);
    const std::string name = p.filename().string();
    removeStaleFoldersOnce(p.parent_path());
    const std::string prefix = "." + name + ".tmp";
    slot_ = makePrivateFolder((p.parent_path() / (prefix + std::to_string(::getpid()) + "-XXXXXX")).string(), folder_);
    path_ = (fs::path(folder_) / name).string();
}

TemporaryFile::~TemporaryFile() { discard(); }

void TemporaryFile::commit() {
    if (done_) throw Error("internal: temporary file '" + path_ + "' committed twice");
    std::error_code ec;
    fs::rename(path_, finalPath_, ec);
    if (ec) {
        discard();
        throw Error("cannot write '" + finalPath_ + "': rename failed (" + ec.message() + ")");
    }
    done_ = true;
    fs::remove_all(folder_, ec);  // the writer's scratch files, if it left any
    releaseSlot(slot_);
}

void TemporaryFile::discard() noexcept {
    if (done_) return;
    done_ = true;
    std::error_code ec;
    fs::remove_all(folder_, ec);
    releaseSlot(slot_);
}

void removeTemporaryFiles() noexcept {
    for (Slot& s : gSlots) {
        int expected = kLive;
        // A slot already removing is removed again: a file may have been created in it since.
        if (s.state.compare_exchange_strong(expected, kRemoving, std::memory_order_acquire) || expected == kRemoving)
            removeFolderSignalSafe(s.path);
    }
}

}  // namespace demlight
