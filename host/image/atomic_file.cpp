#include "image/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "image/fatal_signal_cleanup.h"
#include "util/error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& target, const std::string& what, int err) {
    throw RuntimeError("cannot write '" + target.string() + "': " + what + ": " +
                       std::strerror(err));
}

/// Removes the temporary file unless released after a successful rename; a process
/// ended by a signal meanwhile removes it too.
struct TempGuard {
    fs::path path;
    RemovedOnFatalSignal on_signal{path};
    bool active = true;
    ~TempGuard() {
        if (active) {
            std::error_code ec;
            fs::remove(path, ec);
        }
    }
};

/// Writes all of `size` bytes to `fd`, retrying on EINTR and short writes.
bool write_all(int fd, const char* data, std::size_t size) {
    while (size > 0) {
        ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

/// Best effort: makes the rename itself durable. Failure here does not undo the write.
void sync_directory(const fs::path& target) {
    fs::path dir = target.parent_path();
    int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

/// The process umask, read without changing it (umask(2) would race with other threads).
mode_t current_umask() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("Umask:", 0) == 0) return static_cast<mode_t>(std::stoul(line.substr(6), nullptr, 8));
    return 022;
}

/// Creates the temporary file beside `target`; returns its open descriptor. Where the
/// target's directory had to be made, *made (when given) is the outermost one made.
int make_temp(const fs::path& target, fs::path& temp, fs::path* made = nullptr) {
    if (target.filename().empty())
        throw RuntimeError("cannot write '" + target.string() + "': not a file name");
    fs::path dir = target.parent_path();
    // The run's output directories are made here, at its first write, not when its options
    // are checked: a run that fails before writing leaves no directory behind.
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        // The outermost directory to be made: the one just below the existing ancestor.
        const fs::path existing = existing_ancestor(dir);
        fs::path outermost = dir;
        while (outermost.has_parent_path() && outermost.parent_path() != existing &&
               outermost.parent_path() != outermost)
            outermost = outermost.parent_path();
        fs::create_directories(dir, ec);
        if (ec) fail(target, "cannot create the directory '" + dir.string() + "'", ec.value());
        if (made) *made = outermost;
    }
    static constexpr char kSuffix[] = ".tmp.XXXXXX";
    static_assert(1 + sizeof kSuffix - 1 == kTemporaryNameExtra, "the leading '.' and the suffix");
    std::string pattern = (dir.empty() ? fs::path(".") : dir).string() + "/." + target.filename().string() + kSuffix;
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    int fd = ::mkstemp(buf.data());
    if (fd < 0) {
        int err = errno;
        fail(target, "cannot create a temporary file in '" +
                         (dir.empty() ? std::string(".") : dir.string()) + "'",
             err);
    }
    temp = fs::path(buf.data());
    // mkstemp creates 0600; give the file the mode a plain open(O_CREAT, 0666) would.
    ::fchmod(fd, 0666 & ~current_umask());
    return fd;
}

/// Gives the temporary the permission bits of the file it is about to replace, so that a
/// replaced image stays as private, or as read-only, as it was (mkstemp's file has the
/// umask's mode); nothing where no file is there yet. Just before the rename: a read-only
/// mode earlier would stop a writer that reopens the temporary by name.
void keep_mode(const fs::path& target, const fs::path& temp) {
    struct stat st;
    if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) ::chmod(temp.c_str(), st.st_mode & 07777);
}

void sync_and_rename(const fs::path& target, TempGuard& guard) {
    int fd = ::open(guard.path.c_str(), O_RDONLY);
    if (fd < 0) fail(target, "cannot reopen the temporary file", errno);
    if (::fsync(fd) != 0) {
        int err = errno;
        ::close(fd);
        fail(target, "fsync failed", err);
    }
    if (::close(fd) != 0) fail(target, "close failed", errno);
    keep_mode(target, guard.path);
    std::error_code ec;
    fs::rename(guard.path, target, ec);
    if (ec) fail(target, "rename failed", ec.value());
    guard.active = false;
    sync_directory(target);
}

}  // namespace

fs::path output_target(const fs::path& path) {
    std::error_code ec;
    fs::path p = path;
    // 40 links at most, as the kernel's path resolution (ELOOP): a loop ends here.
    for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++hops) {
        const fs::path next = fs::read_symlink(p, ec);
        if (ec) return path;
        p = next.is_absolute() ? next : p.parent_path() / next;
    }
    return p;
}

fs::path existing_ancestor(const fs::path& dir) {
    std::error_code ec;
    fs::path at = dir.empty() ? fs::path(".") : dir;
    // symlink_status: a link to nothing is where creating the directory would fail, so
    // the walk stops there and the caller can name it.
    for (fs::path next; !fs::exists(fs::symlink_status(at, ec)); at = next) {
        next = at.has_parent_path() ? at.parent_path() : fs::path(".");
        if (next == at) break;  // "/" or "." itself missing
    }
    return at;
}

void write_file_atomic(const fs::path& link, const void* data, std::size_t size) {
    const fs::path path = output_target(link);
    fs::path temp;
    int fd = make_temp(path, temp);
    TempGuard guard{temp};
    if (!write_all(fd, static_cast<const char*>(data), size)) {
        int err = errno;
        ::close(fd);
        fail(path, "write failed", err);
    }
    if (::fsync(fd) != 0) {
        int err = errno;
        ::close(fd);
        fail(path, "fsync failed", err);
    }
    if (::close(fd) != 0) fail(path, "close failed", errno);
    keep_mode(path, temp);
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) fail(path, "rename failed", ec.value());
    guard.active = false;
    sync_directory(path);
}

void replace_file_atomic(const fs::path& link,
                         const std::function<void(const fs::path& temp)>& write) {
    const fs::path path = output_target(link);
    fs::path temp;
    int fd = make_temp(path, temp);
    TempGuard guard{temp};
    ::close(fd);
    write(temp);
    sync_and_rename(path, guard);
}

CommitGroup::~CommitGroup() {
    std::error_code ec;
    for (const Entry& e : entries_) {
        if (!e.renamed) fs::remove(e.temp, ec);
        if (!e.backup.empty()) fs::remove(e.backup, ec);
    }
    // A directory the group made for its targets goes too when nothing landed in it (the
    // group failed): a failing run leaves no directory behind. Newest first.
    for (auto d = made_dirs_.rbegin(); d != made_dirs_.rend(); ++d) {
        bool empty = true;
        for (auto it = fs::recursive_directory_iterator(*d, ec); empty && !ec && it != fs::recursive_directory_iterator();
             it.increment(ec))
            empty = it->is_directory(ec);
        if (empty && !ec) fs::remove_all(*d, ec);
    }
}

fs::path CommitGroup::add(const fs::path& link) {
    const fs::path target = output_target(link);
    fs::path temp, made;
    const int fd = make_temp(target, temp, &made);
    ::close(fd);
    if (!made.empty()) {
        made_dirs_.push_back(made);
        // Each level, for a signal that skips the destructor (outermost first; the
        // handler removes the empty ones innermost first).
        std::vector<fs::path> levels;
        for (fs::path d = target.parent_path(); !d.empty() && d != made.parent_path(); d = d.parent_path())
            levels.push_back(d);
        for (auto d = levels.rbegin(); d != levels.rend(); ++d)
            made_dirs_on_signal_.push_back(RemovedOnFatalSignal::directory(*d));
    }
    entries_.push_back({target, temp, {}, link, RemovedOnFatalSignal(temp)});
    return temp;
}

void CommitGroup::write(const fs::path& target, const std::function<void(const fs::path& temp)>& fill) {
    const fs::path temp = add(target);
    naming_targets([&] { fill(temp); });
}

std::string CommitGroup::shown(std::string message) const {
    for (const Entry& e : entries_) message = with_path_shown(std::move(message), e.temp, e.asked);
    return message;
}

void CommitGroup::naming_targets(const std::function<void()>& work) const {
    try {
        work();
    } catch (const RuntimeError& e) {
        std::string message = shown(e.what());
        if (message == e.what()) throw;  // not about a temporary: as it was, type and all
        throw RuntimeError(message);
    }
}

std::string with_path_shown(std::string message, const fs::path& temp, const fs::path& shown) {
    const std::string from = temp.string(), to = shown.string();
    if (from.empty()) return message;
    for (size_t at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
        message.replace(at, from.size(), to);
    return message;
}

void CommitGroup::commit() {
    // Keep each file about to be replaced under a second name (a hard link: no copy), so
    // a later rename failing can put it back.
    for (Entry& e : entries_) {
        e.existed = fs::exists(e.target);
        if (!fs::is_regular_file(e.target)) continue;
        fs::path link;
        ::close(make_temp(e.target, link));
        fs::remove(link);
        if (::link(e.target.c_str(), link.c_str()) == 0) e.backup = link;  // else: no roll-back for this one
    }
    for (Entry& e : entries_) {
        keep_mode(e.target, e.temp);
        std::error_code ec;
        fs::rename(e.temp, e.target, ec);
        if (ec) {
            roll_back();
            fail(e.target, "rename failed", ec.value());
        }
        e.renamed = true;
    }
    for (Entry& e : entries_) {
        e.on_signal = {};  // its name is gone: nothing for a signal to remove
        sync_directory(e.target);
    }
    // The old files' second names are not needed once all landed: removed now, not in
    // the destructor, which a signal held through the commit (SignalsHeld) never reaches.
    std::error_code ec;
    for (Entry& e : entries_)
        if (!e.backup.empty()) {
            fs::remove(e.backup, ec);
            e.backup.clear();
        }
}

void CommitGroup::roll_back() {
    std::error_code ec;
    for (Entry& e : entries_) {
        if (!e.renamed) continue;
        if (!e.existed)
            fs::remove(e.target, ec);
        else if (!e.backup.empty() && (fs::rename(e.backup, e.target, ec), !ec))
            e.backup.clear();
        e.renamed = false;
        e.temp.clear();
    }
}

}  // namespace tessera
