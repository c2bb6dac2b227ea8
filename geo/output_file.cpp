// Output files; see output_file.h.
#include "geo/output_file.h"

#include "src/error.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
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

/// One temporary path. The state moves kFree -> kFilling (a writer claims it and copies the
/// path) -> kLive -> kFree (committed or removed), or kLive -> kRemoving (removeTemporaryFiles).
struct Slot {
    std::atomic<int> state{kFree};
    char path[kMaxTemporaryPath];
};
static_assert(std::atomic<int>::is_always_lock_free);

// The one piece of process-wide mutable state in the library, and why: a signal handler that
// ends the process at once can reach nothing else (no locks, no allocation), so the paths to
// remove must already sit in static storage.
Slot gSlots[kMaxTemporaries];

int claimSlot(const std::string& path) {
    if (path.size() >= kMaxTemporaryPath) return -1;
    for (std::size_t i = 0; i < kMaxTemporaries; ++i) {
        int expected = kFree;
        if (!gSlots[i].state.compare_exchange_strong(expected, kFilling, std::memory_order_acquire)) continue;
        std::memcpy(gSlots[i].path, path.c_str(), path.size() + 1);
        gSlots[i].state.store(kLive, std::memory_order_release);
        return static_cast<int>(i);
    }
    return -1;
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
        return "file too large for the file size limit (ulimit -f) or the file system (" +
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

}  // namespace

void checkNotInput(const std::string& path, const std::string& inputPath) {
    std::error_code ec;
    if (!inputPath.empty() && fs::exists(path, ec) && fs::equivalent(fs::path(path), fs::path(inputPath), ec))
        throw Error("output '" + path + "' would overwrite its input; choose another -o");
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

void removeEarlierOutputs(const std::string& dir, const std::function<bool(const std::string& name)>& isEarlierOutput) {
    // A temporary name is the final one, hidden or not, with ".tmp<pid>" after it (TemporaryFile).
    const auto finalName = [](std::string name) {
        const auto tmp = name.rfind(".tmp");
        if (tmp == std::string::npos || tmp + 4 == name.size() ||
            !std::all_of(name.begin() + static_cast<std::ptrdiff_t>(tmp) + 4, name.end(),
                         [](unsigned char c) { return std::isdigit(c); }))
            return name;
        name.erase(tmp);
        if (name.starts_with('.')) name.erase(0, 1);
        return name;
    };
    std::error_code ec;
    std::vector<fs::path> earlier;
    for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.is_regular_file(ec) && isEarlierOutput(finalName(e.path().filename().string()))) earlier.push_back(e.path());
    for (const auto& p : earlier)
        if (!fs::remove(p, ec) && ec) throw Error("cannot remove '" + p.string() + "' of an earlier run (" + ec.message() + ")");
}

std::string diagnoseWriteFailure(const std::string& path) {
    int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    std::string probe;
    if (fd < 0) {
        std::error_code ec;
        probe = (fs::absolute(fs::path(path), ec).parent_path() / (".demlight-probe-" + std::to_string(::getpid())))
                    .string();
        fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
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

TemporaryFile::TemporaryFile(const std::string& finalPath, TemporaryNaming naming) : finalPath_(finalPath) {
    std::error_code ec;
    const fs::path p = fs::absolute(fs::path(finalPath), ec);
    std::string name = naming == TemporaryNaming::Hidden ? "." : "";
    name += p.filename().string();
    name += ".tmp" + std::to_string(::getpid());
    path_ = (p.parent_path() / name).string();
    slot_ = claimSlot(path_);
}

TemporaryFile::TemporaryFile(const std::string& scratchPath) : path_(scratchPath) {
    std::error_code ec;
    path_ = fs::absolute(fs::path(scratchPath), ec).string();
    slot_ = claimSlot(path_);
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
    releaseSlot(slot_);
}

void TemporaryFile::discard() noexcept {
    if (done_) return;
    done_ = true;
    ::unlink(path_.c_str());
    releaseSlot(slot_);
}

void removeTemporaryFiles() noexcept {
    for (Slot& s : gSlots) {
        int expected = kLive;
        // A slot already removing is unlinked again: its file may have been created since.
        if (s.state.compare_exchange_strong(expected, kRemoving, std::memory_order_acquire) || expected == kRemoving)
            ::unlink(s.path);
    }
}

}  // namespace demlight
