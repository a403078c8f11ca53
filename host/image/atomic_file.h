// Atomic file replacement: content goes to a unique temporary file in the target's
// directory, which is renamed over the target only after a complete, synced write. A
// missing directory is made at that first write (the CLI's checks make none, so a run
// that fails before it writes leaves nothing behind). A replaced file keeps its
// permission bits, and a target that is a symbolic link to a file replaces that file
// (the link stays a link).
#pragma once
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "image/fatal_signal_cleanup.h"

namespace tessera {

/// The directory a missing one would be made in: `dir` itself where it exists, else its
/// nearest existing ancestor (a symbolic link counts as existing, even one to nothing);
/// "." for an empty `dir` and for a relative one none of whose
/// ancestors exists. Only where "/" or "." itself is missing is the result missing too.
/// The CLI's checks probe it before a run; the writer makes the directories below it.
std::filesystem::path existing_ancestor(const std::filesystem::path& dir);

/// The file a write to `path` replaces: where `path` is a symbolic link (to a file, or to
/// nothing yet), the file it names, followed through further links; else `path`.
/// Renaming over the link would turn it into a plain file and leave the file it names as
/// it was. The CLI's checks probe this file's directory.
std::filesystem::path output_target(const std::filesystem::path& path);

/// `message` with every occurrence of the temporary file `temp`'s path replaced by
/// `shown`'s: a library's error about the temporary it wrote names the file asked for.
std::string with_path_shown(std::string message, const std::filesystem::path& temp, const std::filesystem::path& shown);

/// Writes `size` bytes atomically to `path`. Throws RuntimeError naming `path` and the
/// OS reason on failure; an existing file at `path` is then left untouched.
void write_file_atomic(const std::filesystem::path& path, const void* data, std::size_t size);

/// The bytes a temporary's name, `.<name>.tmp.XXXXXX`, adds to its target's.
inline constexpr std::size_t kTemporaryNameExtra = 12;
/// The most an output's name grows on its way to the file: a run's EXR goes to a
/// CommitGroup temporary, which write_exr fills through a temporary of its own
/// (`..<name>.tmp.XXXXXX.tmp.XXXXXX`). A target whose name is within this of its
/// directory's limit (NAME_MAX, 255 bytes on Linux's file systems) cannot be written, so
/// the output checks refuse it before any work.
inline constexpr std::size_t kOutputNameExtra = 2 * kTemporaryNameExtra;

/// Creates a unique empty temporary file `.<name>.tmp.XXXXXX` beside `path`, calls
/// `write(temp)` to fill it (the callback may reopen the file by name), fsyncs it and
/// renames it over `path`. On any failure (including an exception from `write`) the
/// temporary is removed; OS failures throw RuntimeError naming `path`, exceptions from
/// `write` propagate unchanged.
void replace_file_atomic(const std::filesystem::path& path,
                         const std::function<void(const std::filesystem::path& temp)>& write);

/// The outputs of one run, written as one unit: each is filled in a temporary beside
/// its target (add), and commit() renames them all over their targets only once every
/// one is complete. A failing run (an exception before commit) leaves no new file and
/// changes no existing one: the destructor removes every temporary, and the directories
/// add() made for them where nothing else landed. A process ended by a signal before
/// commit removes the temporaries too (image/fatal_signal_cleanup.h).
class CommitGroup {
public:
    CommitGroup() = default;
    ~CommitGroup();
    CommitGroup(const CommitGroup&) = delete;
    CommitGroup& operator=(const CommitGroup&) = delete;

    /// Creates an empty temporary `.<name>.tmp.XXXXXX` beside `target` and returns its
    /// path, for the caller to fill (write_exr(temp, ...) replaces it atomically). Throws
    /// RuntimeError naming `target` when the temporary cannot be made.
    std::filesystem::path add(const std::filesystem::path& target);
    /// add(target), then `fill(temp)` to write the temporary, under naming_targets: a
    /// write that fails (a full disk, say) names the file the user asked for, not a
    /// hidden `.<name>.tmp.XXXXXX`.
    void write(const std::filesystem::path& target, const std::function<void(const std::filesystem::path& temp)>& fill);

    /// `message` with the path of every temporary added so far replaced by its target's
    /// as it was given to add() (with_path_shown): what a tool says about a temporary it
    /// filled names the file asked for.
    std::string shown(std::string message) const;
    /// Runs `work`. A RuntimeError from it that names a temporary of the group is
    /// rethrown as RuntimeError(shown(message)); one that names none, and every other
    /// exception, propagates unchanged, type and all.
    void naming_targets(const std::function<void()>& work) const;

    /// Renames every temporary over its target, in the order added. If a rename fails,
    /// the targets already renamed are put back as they were (a replaced file is
    /// restored from a hard link made before; a new one is removed) and RuntimeError
    /// names the target and the OS reason.
    void commit();

private:
    struct Entry {
        std::filesystem::path target, temp, backup;  // backup: empty when no old file was kept
        std::filesystem::path asked;  // the target as given to add(), before links are followed
        RemovedOnFatalSignal on_signal;  // the temporary, should a signal end the process
        bool existed = false;  // a file was at target before commit
        bool renamed = false;
    };
    void roll_back();
    std::vector<Entry> entries_;
    std::vector<std::filesystem::path> made_dirs_;  // outermost directories add() made
    std::vector<RemovedOnFatalSignal> made_dirs_on_signal_;  // every level of them
};

}  // namespace tessera
