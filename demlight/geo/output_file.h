// Output files (docs/design.md §8, docs/outputs.md): each is written in a private folder beside
// its final name and renamed into place on success, so a failure or a signal never leaves a
// partial file under the final name and no planted link is followed. The private folders live in
// a fixed table until they are committed or removed, so that a signal handler can still remove
// them when the process is ended at once.
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

/// An exclusive lock on an output folder for the life of the object (flock(2) on the folder
/// itself, released when the process ends in any way, SIGKILL included), so that two runs never
/// write into one folder at once. Throws Error naming the folder when another process holds it
/// or it cannot be opened.
class FolderLock {
public:
    explicit FolderLock(const std::string& dir);
    ~FolderLock();
    FolderLock(const FolderLock&) = delete;
    FolderLock& operator=(const FolderLock&) = delete;

private:
    int fd_ = -1;
};

/// Removes the regular files in `dir` whose names `isEarlierOutput` accepts, and the temporary
/// files and private folders of such names whose process no longer runs (isTemporaryName);
/// nothing else. Throws Error naming a file that cannot be removed.
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

/// A temporary file for `finalPath`, written in a private folder beside it and renamed out onto
/// the final path by commit(). The folder, ".NAME.tmp<pid>-XXXXXX" in the final path's folder,
/// is made by mkdtemp(3): created exclusively with mode 0700, so no name inside it can have been
/// planted (a link there would redirect the write), and no other user can look in while it is
/// written. The file inside has the final name, so writers that choose a format by extension
/// choose the same one, and their own scratch files (GDAL's COG overviews) land in the folder too.
/// The file keeps the mode its writer gave it (the umask applies), and the rename stays on one
/// file system. The destructor removes the folder and everything in it unless committed; a
/// folder left by a process that no longer runs (SIGKILL) is removed by the next TemporaryFile
/// for the same final path.
class TemporaryFile {
public:
    /// Throws Error naming the folder when the private folder cannot be made.
    explicit TemporaryFile(const std::string& finalPath);
    ~TemporaryFile();
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    /// The file to write: FOLDER/NAME inside the private folder.
    const std::string& path() const { return path_; }
    const std::string& finalPath() const { return finalPath_; }
    /// Renames the file onto the final path and removes the private folder. Throws Error (the
    /// folder removed) on failure.
    void commit();
    /// Removes the folder and its files now (no error if they do not exist).
    void discard() noexcept;

private:
    std::string finalPath_;
    std::string folder_;
    std::string path_;
    int slot_ = -1;  ///< its entry in the table, or -1 when the table was full or the path too long
    bool done_ = false;
};

/// Whether `name` is the name of a TemporaryFile's private folder (".NAME.tmp<pid>-XXXXXX"), or
/// of a temporary file of an earlier demlight ("NAME.tmp<pid>", ".NAME.tmp<pid>"); `finalName`
/// receives NAME.
bool isTemporaryName(const std::string& name, std::string* finalName = nullptr);

/// Throws Error unless a new file can be made in `folder` (a probe made and removed exclusively,
/// so that no planted name there is followed).
void checkFolderAcceptsFiles(const std::string& folder, const std::string& forOutput);

/// Removes the private folder of every temporary file of this process not committed, and the
/// files in it (again for folders being removed: a writer may have created a file after the first
/// pass). Async-signal-safe (atomics, open, getdents64, unlinkat and rmdir over a fixed table):
/// for a handler that ends the process at once, and for std::terminate.
void removeTemporaryFiles() noexcept;

}  // namespace demlight
