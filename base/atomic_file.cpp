#include "base/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace base {
namespace {

std::string system_reason(int error) { return std::strerror(error); }

[[noreturn]] void fail(const std::string& verb, const std::filesystem::path& path, const std::string& why) {
    throw std::runtime_error("cannot " + verb + " " + path.string() + ": " + why);
}

// The live temporaries. The signal thread takes the lock and never gives it
// back, so nothing can register or rename a temporary while it removes them.
struct Temporary {
    Folder folder;
    std::string name;
};
struct Temporaries {
    std::mutex lock;
    std::vector<Temporary> names;
};

Temporaries& temporaries() {
    static Temporaries* all = new Temporaries;  // never destroyed: the signal thread may outlive main's statics
    return *all;
}

void enlist_locked(const Folder& folder, const std::string& name) { temporaries().names.push_back({folder, name}); }

void discharge_locked(const Folder& folder, const std::string& name) {
    auto& names = temporaries().names;
    names.erase(std::remove_if(names.begin(), names.end(),
                               [&](const Temporary& t) { return t.folder.fd() == folder.fd() && t.name == name; }),
                names.end());
}

void enlist(const Folder& folder, const std::string& name) {
    std::lock_guard<std::mutex> hold(temporaries().lock);
    enlist_locked(folder, name);
}

void discharge(const Folder& folder, const std::string& name) {
    std::lock_guard<std::mutex> hold(temporaries().lock);
    discharge_locked(folder, name);
}

// ".NAME~KIND~PID~N": hidden, so no figure id (which cannot start with '.')
// makes it, and '~' ends NAME, which no id contains, so the temporaries of
// "a.png" are never taken for those of "a.png.png".
std::string temporary_name(const std::string& name, const char* kind) {
    static std::atomic<unsigned long> sequence{0};
    return "." + name + "~" + kind + "~" + std::to_string(::getpid()) + "~" + std::to_string(sequence++);
}

bool remove_at_fd(int dir, const char* name) {
    if (::unlinkat(dir, name, 0) == 0) return true;
    if (errno != EISDIR && errno != EPERM) return false;
    const int sub = ::openat(dir, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (sub < 0) return false;
    DIR* listing = ::fdopendir(sub);
    if (!listing) {
        ::close(sub);
        return false;
    }
    std::vector<std::string> inside;
    while (const dirent* entry = ::readdir(listing))
        if (std::strcmp(entry->d_name, ".") != 0 && std::strcmp(entry->d_name, "..") != 0)
            inside.emplace_back(entry->d_name);
    for (const std::string& n : inside) remove_at_fd(::dirfd(listing), n.c_str());
    ::closedir(listing);
    return ::unlinkat(dir, name, AT_REMOVEDIR) == 0;
}

// What stands at `name` in `folder`, not following a symlink: 0 when nothing.
mode_t standing(const Folder& folder, const std::string& name) {
    struct stat st {};
    if (::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return 0;
    return st.st_mode & S_IFMT;
}

// Puts every move's temporary in place of its final name, all or none (see
// CommitGroup). Call with the list's lock held. On failure, the temporaries
// are left for the caller to remove and the error names the final path.
void put_in_place(const std::vector<CommitGroup::Move>& moves) {
    for (const auto& m : moves) {
        const mode_t there = standing(m.folder, m.to);
        if (!m.is_folder && there == S_IFDIR) fail("write", m.folder / m.to, "a folder stands where the file goes");
        if (m.is_folder && there != 0 && there != S_IFDIR && there != S_IFLNK)
            fail("write", m.folder / m.to, "a file stands where the folder goes");
    }
    struct Done {
        const CommitGroup::Move* move;
        std::string old;  // the earlier output, moved aside; empty if there was none
        bool moved_in;
    };
    std::vector<Done> done;
    const auto undo = [&] {
        for (auto d = done.rbegin(); d != done.rend(); ++d) {
            const int dir = d->move->folder.fd();
            if (d->moved_in) ::renameat(dir, d->move->to.c_str(), dir, d->move->from.c_str());
            if (!d->old.empty()) ::renameat(dir, d->old.c_str(), dir, d->move->to.c_str());
        }
    };
    for (const auto& m : moves) {
        const int dir = m.folder.fd();
        done.push_back({&m, "", false});
        if (standing(m.folder, m.to) != 0) {
            // A folder cannot be renamed over another, and an old file moved
            // aside can be moved back: every output is replaced the same way.
            const std::string old = temporary_name(m.to, "old");
            if (::renameat(dir, m.to.c_str(), dir, old.c_str()) != 0) {
                const int error = errno;
                undo();
                fail("write", m.folder / m.to, system_reason(error));
            }
            done.back().old = old;
        }
        if (::renameat(dir, m.from.c_str(), dir, m.to.c_str()) != 0) {
            const int error = errno;
            undo();
            fail("write", m.folder / m.to, system_reason(error));
        }
        done.back().moved_in = true;
    }
    for (const Done& d : done) {
        discharge_locked(d.move->folder, d.move->from);
        if (!d.old.empty()) remove_at_fd(d.move->folder.fd(), d.old.c_str());
    }
}

thread_local CommitGroup* current_group = nullptr;

}  // namespace

// ---- Folder -----------------------------------------------------------------

Folder::Handle::~Handle() { ::close(fd); }

Folder::Folder(int fd, std::filesystem::path path) : handle_(std::make_shared<Handle>(fd)), path_(std::move(path)) {}

Folder::Folder(const std::filesystem::path& path, bool create) : path_(path) {
    if (create) {
        std::error_code ec;
        std::filesystem::create_directories(path, ec);
        if (ec) fail("create the folder", path, ec.message());
    }
    const int fd = ::open(path.empty() ? "." : path.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) fail("open the folder", path, system_reason(errno));
    handle_ = std::make_shared<Handle>(fd);
}

Folder::Folder(const Folder& parent, const std::string& name) : path_(parent / name) {
    for (int attempt = 0; attempt < 8; ++attempt) {
        const int fd = ::openat(parent.fd(), name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (fd >= 0) {
            handle_ = std::make_shared<Handle>(fd);
            return;
        }
        if (errno == ENOENT) {
            if (::mkdirat(parent.fd(), name.c_str(), 0777) != 0 && errno != EEXIST)
                fail("create the folder", path_, system_reason(errno));
        } else if (errno == ELOOP || errno == ENOTDIR) {
            remove_at_fd(parent.fd(), name.c_str());  // a symlink or a file where the folder goes
        } else {
            fail("open the folder", path_, system_reason(errno));
        }
    }
    fail("open the folder", path_, "it keeps changing");
}

// ---- AtomicFile -------------------------------------------------------------

AtomicFile::AtomicFile(Folder folder, std::string name, Commit when)
    : folder_(std::move(folder)), name_(std::move(name)), when_(when) {
    // A fresh name each time: one planted in advance is skipped, never opened.
    for (int attempt = 0; fd_ < 0; ++attempt) {
        temp_ = temporary_name(name_, "tmp");
        fd_ = ::openat(folder_.fd(), temp_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd_ < 0 && (errno != EEXIST || attempt == 100)) fail("write", final_path(), system_reason(errno));
    }
    enlist(folder_, temp_);
}

std::optional<Folder> Folder::inside(const Folder& parent, const std::string& name) {
    const int fd = ::openat(parent.fd(), name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) return std::nullopt;
    return Folder(fd, parent / name);
}

Folder Folder::of(const std::filesystem::path& path) {
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) fail("write", path, system_reason(errno));
    return Folder(fd, folder);
}

AtomicFile::AtomicFile(const std::filesystem::path& final_path)
    : AtomicFile(Folder::of(final_path), final_path.filename().string()) {}

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) {
        ::unlinkat(folder_.fd(), temp_.c_str(), 0);
        discharge(folder_, temp_);
    }
}

std::FILE* AtomicFile::take_stream() {
    std::FILE* stream = ::fdopen(fd_, "w+b");
    if (!stream) fail("write", final_path(), system_reason(errno));
    fd_ = -1;
    return stream;
}

void AtomicFile::close_checked() {
    if (fd_ < 0) return;
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("write", final_path(), system_reason(errno));
}

void AtomicFile::commit() {
    close_checked();
    if (CommitGroup* group = CommitGroup::current(); group && when_ == Commit::with_group) {
        group->defer({folder_, temp_, name_, false});  // still on the list of temporaries until the group commits
        committed_ = true;
        return;
    }
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        put_in_place({{folder_, temp_, name_, false}});
    }
    committed_ = true;
}

// ---- AtomicDir --------------------------------------------------------------

AtomicDir::AtomicDir(const Folder& parent, std::string name) : parent_(parent), name_(std::move(name)) {
    for (int attempt = 0;; ++attempt) {
        temp_ = temporary_name(name_, "tmp");
        if (::mkdirat(parent_.fd(), temp_.c_str(), 0777) == 0) break;
        if (errno != EEXIST || attempt == 100) fail("create", parent_ / name_, system_reason(errno));
    }
    enlist(parent_, temp_);
    try {
        inside_ = std::make_unique<Folder>(parent_, temp_);
    } catch (...) {
        remove_at_fd(parent_.fd(), temp_.c_str());
        discharge(parent_, temp_);
        throw;
    }
}

AtomicDir::~AtomicDir() {
    inside_.reset();
    if (!committed_) {
        remove_at_fd(parent_.fd(), temp_.c_str());
        discharge(parent_, temp_);
    }
}

void AtomicDir::commit() {
    if (CommitGroup* group = CommitGroup::current()) {
        group->defer({parent_, temp_, name_, true});
        committed_ = true;
        return;
    }
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        put_in_place({{parent_, temp_, name_, true}});
    }
    committed_ = true;
}

// ---- CommitGroup ------------------------------------------------------------

CommitGroup::CommitGroup() : outer_(current_group) { current_group = this; }

CommitGroup* CommitGroup::current() { return current_group; }

CommitGroup::~CommitGroup() {
    if (current_group == this) current_group = outer_;
    if (committed_) return;
    for (const Move& move : moves_) {
        remove_at_fd(move.folder.fd(), move.from.c_str());
        discharge(move.folder, move.from);
    }
}

void CommitGroup::commit() {
    current_group = outer_;  // from here on, commits are immediate again
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        put_in_place(moves_);  // on failure the destructor removes the temporaries
    }
    committed_ = true;
}

// ---- the rest ---------------------------------------------------------------

bool remove_at(const Folder& folder, const std::string& name) { return remove_at_fd(folder.fd(), name.c_str()); }

int remove_stale_temporaries(const Folder& folder, const std::vector<std::string>& names) {
    const int fd = ::openat(folder.fd(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return 0;
    DIR* listing = ::fdopendir(fd);
    if (!listing) {
        ::close(fd);
        return 0;
    }
    std::vector<std::string> stale;
    while (const dirent* entry = ::readdir(listing)) {
        const std::string found = entry->d_name;
        for (const std::string& name : names)
            if (found.rfind("." + name + "~tmp~", 0) == 0 || found.rfind("." + name + "~old~", 0) == 0)
                stale.push_back(found);
    }
    ::closedir(listing);
    int removed = 0;
    for (const std::string& name : stale) removed += remove_at(folder, name);
    return removed;
}

int open_regular_at(const Folder& folder, const std::string& name) {
    const int fd = ::openat(folder.fd(), name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return -1;
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        const int reason = st.st_mode == 0 ? errno : EINVAL;  // fstat's error, or not a regular file
        ::close(fd);
        errno = reason;
        return -1;
    }
    // A regular file never blocks; readers that poll would be surprised by O_NONBLOCK.
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

std::string not_opened_reason(int err) {
    if (err == EINVAL) return "it is not a regular file";
    if (err == ELOOP) return "it is a symlink, which is not followed";
    return std::strerror(err);
}

std::optional<std::string> read_file_at(const Folder& folder, const std::string& name, std::size_t max_bytes) {
    const int fd = open_regular_at(folder, name);
    if (fd < 0) return std::nullopt;
    std::optional<std::string> text;
    struct stat st {};
    // A file larger than asked is refused before anything is read or allocated.
    if (::fstat(fd, &st) == 0 && static_cast<std::uintmax_t>(st.st_size) <= max_bytes) {
        text.emplace();
        char chunk[1 << 16];
        ssize_t n = 0;
        while ((n = ::read(fd, chunk, sizeof chunk)) > 0 && text->size() <= max_bytes)
            text->append(chunk, static_cast<std::size_t>(n));
        if (n < 0 || text->size() > max_bytes) text.reset();
    }
    ::close(fd);
    return text;
}

void write_file_atomically(const Folder& folder, const std::string& name, const std::string& bytes,
                           AtomicFile::Commit when) {
    AtomicFile file(folder, name, when);
    for (std::size_t written = 0; written < bytes.size();) {
        const ssize_t n = ::write(file.fd(), bytes.data() + written, bytes.size() - written);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail("write", file.final_path(), system_reason(errno));
        written += static_cast<std::size_t>(n);
    }
    file.commit();
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
    write_file_atomically(Folder::of(path), path.filename().string(), bytes);
}

void remove_on_signal(const Folder& folder, const std::string& name) { enlist(folder, name); }
void keep_on_signal(const Folder& folder, const std::string& name) { discharge(folder, name); }

namespace {
int remove_all_listed() noexcept {
    int removed = 0;
    for (const Temporary& t : temporaries().names) removed += remove_at_fd(t.folder.fd(), t.name.c_str());
    return removed;
}
}  // namespace

void remove_temporaries_now() noexcept {
    // This thread may hold the lock already (an exception in the middle of a commit).
    const bool held = temporaries().lock.try_lock();
    remove_all_listed();
    if (held) temporaries().lock.unlock();
}

void remove_temporaries_on_signals() {
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    sigaddset(&signals, SIGHUP);
    if (const int error = pthread_sigmask(SIG_BLOCK, &signals, nullptr))
        throw std::runtime_error(std::string("cannot block signals: ") + std::strerror(error));
    std::thread([signals] {
        int signal = 0;
        if (sigwait(&signals, &signal) != 0) return;
        temporaries().lock.lock();  // kept: nothing renames or adds a temporary from here on
        const int removed = remove_all_listed();
        std::fprintf(stderr, "\nfiggen: %s: stopped; %d unfinished output%s removed, finished ones kept\n",
                     strsignal(signal), removed, removed == 1 ? "" : "s");
        std::fflush(stderr);
        ::_exit(128 + signal);
    }).detach();
}

}  // namespace base
