#include "render/atomic_file.hpp"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

namespace render {
namespace {

// The live temporaries. The signal thread takes the lock and never gives it
// back, so nothing can register or rename a temporary while it removes them.
struct Temporaries {
    std::mutex lock;
    std::set<std::filesystem::path> paths;
};

Temporaries& temporaries() {
    static Temporaries* all = new Temporaries;  // never destroyed: the signal thread may outlive main's statics
    return *all;
}

void enlist(const std::filesystem::path& path) {
    std::lock_guard<std::mutex> hold(temporaries().lock);
    temporaries().paths.insert(path);
}

void discharge(const std::filesystem::path& path) {
    std::lock_guard<std::mutex> hold(temporaries().lock);
    temporaries().paths.erase(path);
}

// Same folder as the final file, so the rename never crosses filesystems; the
// pid keeps two processes writing the same figure into one folder apart.
std::filesystem::path temporary_for(const std::filesystem::path& final_path) {
    std::filesystem::path temp = final_path;
    temp += ".tmp-" + std::to_string(::getpid());
    return temp;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path final_path)
    : final_(std::move(final_path)), temp_(temporary_for(final_)) {
    enlist(temp_);
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(temp_, ignored);
        discharge(temp_);
    }
}

void AtomicFile::commit() {
    if (CommitGroup* group = CommitGroup::current()) {
        group->defer({temp_, final_, false});  // still on the list of temporaries until the group commits
        committed_ = true;
        return;
    }
    std::error_code ec;
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        std::filesystem::rename(temp_, final_, ec);
        if (!ec) temporaries().paths.erase(temp_);
    }
    if (ec) throw std::runtime_error("cannot write " + final_.string() + ": " + ec.message());
    committed_ = true;
}

AtomicDir::AtomicDir(std::filesystem::path final_path)
    : final_(std::move(final_path)), temp_(temporary_for(final_)) {
    enlist(temp_);
    std::error_code ec;
    std::filesystem::remove_all(temp_, ec);  // left by an earlier process of the same pid
    std::filesystem::create_directories(temp_, ec);
    if (ec) {
        discharge(temp_);
        throw std::runtime_error("cannot create " + temp_.string() + ": " + ec.message());
    }
}

AtomicDir::~AtomicDir() {
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove_all(temp_, ignored);
        discharge(temp_);
    }
}

namespace {

// Puts a finished folder in place of `final_path`. Call with the list's lock held.
void swap_folder_locked(const std::filesystem::path& temp, const std::filesystem::path& final_path,
                        std::error_code& ec) {
    // A folder cannot be renamed over a full one: move the old one aside
    // (under a temporary name, so an interruption removes it), move the new
    // one in; the caller removes the old.
    std::filesystem::path old = final_path;
    old += ".old-" + std::to_string(::getpid());
    if (std::filesystem::exists(final_path)) {
        std::filesystem::rename(final_path, old, ec);
        if (ec) return;
        temporaries().paths.insert(old);
    }
    std::filesystem::rename(temp, final_path, ec);
    if (!ec) temporaries().paths.erase(temp);
}

void remove_old_folder(const std::filesystem::path& final_path) {
    std::filesystem::path old = final_path;
    old += ".old-" + std::to_string(::getpid());
    std::error_code ignored;
    std::filesystem::remove_all(old, ignored);
    discharge(old);
}

thread_local CommitGroup* current_group = nullptr;

}  // namespace

void AtomicDir::commit() {
    if (CommitGroup* group = CommitGroup::current()) {
        group->defer({temp_, final_, true});
        committed_ = true;
        return;
    }
    std::error_code ec;
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        swap_folder_locked(temp_, final_, ec);
    }
    if (ec) throw std::runtime_error("cannot write " + final_.string() + ": " + ec.message());
    committed_ = true;
    remove_old_folder(final_);
}

CommitGroup::CommitGroup() : outer_(current_group) { current_group = this; }

CommitGroup* CommitGroup::current() { return current_group; }

CommitGroup::~CommitGroup() {
    current_group = outer_;
    if (committed_) return;
    for (const Move& move : moves_) {
        std::error_code ignored;
        std::filesystem::remove_all(move.from, ignored);
        discharge(move.from);
    }
}

void CommitGroup::commit() {
    current_group = outer_;  // from here on, commits are immediate again
    committed_ = true;
    std::error_code ec;
    std::size_t done = 0;
    {
        std::lock_guard<std::mutex> hold(temporaries().lock);
        for (; done < moves_.size() && !ec; ++done) {
            const Move& move = moves_[done];
            if (move.folder) {
                swap_folder_locked(move.from, move.to, ec);
            } else {
                std::filesystem::rename(move.from, move.to, ec);
                if (!ec) temporaries().paths.erase(move.from);
            }
        }
    }
    for (const Move& move : moves_)
        if (move.folder) remove_old_folder(move.to);
    if (ec) {
        const Move failed = moves_[done - 1];
        for (std::size_t i = done - 1; i < moves_.size(); ++i) {  // the ones not in place
            std::error_code ignored;
            std::filesystem::remove_all(moves_[i].from, ignored);
            discharge(moves_[i].from);
        }
        throw std::runtime_error("cannot write " + failed.to.string() + ": " + ec.message());
    }
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes) {
    AtomicFile file(path);
    std::FILE* f = std::fopen(file.temp_path().c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
    const bool wrote = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const int write_errno = errno;
    // fclose flushes: a full disk often shows up only here.
    const bool closed = std::fclose(f) == 0;
    if (!wrote || !closed)
        throw std::runtime_error("cannot write " + path.string() + ": " +
                                 std::strerror(wrote ? errno : write_errno));
    file.commit();
}

void remove_on_signal(const std::filesystem::path& path) { enlist(path); }
void keep_on_signal(const std::filesystem::path& path) { discharge(path); }

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
        int removed = 0;
        for (const auto& path : temporaries().paths) {
            std::error_code ignored;
            removed += std::filesystem::remove_all(path, ignored) > 0;
        }
        std::fprintf(stderr, "\nfiggen: %s: stopped; %d unfinished output%s removed, finished ones kept\n",
                     strsignal(signal), removed, removed == 1 ? "" : "s");
        std::fflush(stderr);
        ::_exit(128 + signal);
    }).detach();
}

}  // namespace render
