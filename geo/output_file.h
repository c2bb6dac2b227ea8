// Output files (docs/design.md §8): each is written under a temporary name beside its final
// one and renamed into place on success, so a failure or a signal never leaves a partial file
// under the final name. The temporary names live in a fixed table until they are committed or
// removed, so that a signal handler can still remove them when the process is ended at once.
#pragma once

#include <functional>
#include <string>

namespace demlight {

/// Throws Error unless `path` can become an output file: not empty, in an existing folder, and
/// absent or a regular file. A directory, a device (/dev/null, /dev/full), a fifo or a socket is
/// refused: committing an output renames a new file over its path, which would replace the node
/// (as root, a GeoTIFF where /dev/null was).
void checkOutputFile(const std::string& path);

/// Throws Error if `path` is the file `inputPath` names (an empty inputPath: nothing to check):
/// an output renamed over its input would destroy it.
void checkNotInput(const std::string& path, const std::string& inputPath);

/// Throws unless `dir` can become an output folder (a folder of files written by one run): missing
/// (the caller creates it), an empty folder, or, with `replaceEarlier`, any folder. A file, a
/// device or a fifo at `dir` is refused (Error); a folder that is not empty without
/// `replaceEarlier` too (FieldError "overwrite"), since the files of two runs would mix.
void checkOutputFolder(const std::string& dir, bool replaceEarlier);

/// Removes the regular files in `dir` whose names `isEarlierOutput` accepts, and the temporary
/// files of such names (".NAME.tmpPID", "NAME.tmpPID"); nothing else. Throws Error naming a
/// file that cannot be removed.
void removeEarlierOutputs(const std::string& dir, const std::function<bool(const std::string& name)>& isEarlierOutput);

/// Why writing `path` failed at the file-system level, when that can be told, e.g. "the disk is
/// full (No space left on device)" or "the file is too large for the file size limit (ulimit -f;
/// File too large)"; empty otherwise. GDAL and OpenImageIO do not always pass the system's reason
/// on, so this tries to append a little more to the file itself (or to a probe file beside it
/// when it does not exist) and names the error that gives.
std::string diagnoseWriteFailure(const std::string& path);

/// The message of a failed write: "cannot write <subject>: <diagnosis> (<reason>)", `subject`
/// e.g. "'out.tif'" or "band 2 of 'out.tif'", with the diagnosis of `writtenPath` (the file that
/// was being written, diagnoseWriteFailure) when there is one.
std::string writeFailureMessage(const std::string& subject, const std::string& writtenPath,
                                const std::string& reason);

/// How a temporary name is formed from the final one.
enum class TemporaryNaming {
    Suffix,  ///< "out.tif.tmp<pid>"
    Hidden,  ///< ".out.png.tmp<pid>" (not shown by ls)
};

/// A temporary file beside `finalPath` (same folder, so the rename stays on one file system).
/// Constructing it reserves the name in the process-wide table; the file itself is created by the
/// writer. The destructor removes the file unless it was committed.
class TemporaryFile {
public:
    TemporaryFile(const std::string& finalPath, TemporaryNaming naming);
    /// A temporary file at an exact path that is never committed (another writer's scratch file,
    /// e.g. GDAL's COG overview file): removed at destruction and by removeTemporaryFiles().
    explicit TemporaryFile(const std::string& scratchPath);
    ~TemporaryFile();
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    const std::string& path() const { return path_; }
    const std::string& finalPath() const { return finalPath_; }
    /// Renames the file onto the final path. Throws Error (the temporary file removed) on failure.
    void commit();
    /// Removes the file now (no error if it does not exist).
    void discard() noexcept;

private:
    std::string finalPath_;
    std::string path_;
    int slot_ = -1;  ///< its entry in the table, or -1 when the table was full or the path too long
    bool done_ = false;
};

/// Unlinks every temporary file of this process not committed (again for names being removed: a
/// writer may have created the file after the first unlink). Async-signal-safe (atomics and unlink() over a fixed table): for a handler that ends the
/// process at once, and for std::terminate.
void removeTemporaryFiles() noexcept;

}  // namespace demlight
