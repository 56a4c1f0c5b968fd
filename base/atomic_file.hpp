#pragma once
// Every output is written under a temporary name in its final folder and
// renamed over the final name only once complete, so a crash, a full disk or
// an error never leaves a half-written file under the real name.
//
// Names are made relative to an open Folder (openat and friends), never by
// joining paths: a temporary is created exclusively and never through a
// symlink (O_CREAT | O_EXCL | O_NOFOLLOW), and the rename that puts it in
// place replaces a symlink standing at the final name instead of writing
// through it. A temporary's name is hidden and marked, ".NAME~tmp~PID~N",
// so that it can be told from every output and removed once its writer is
// gone (remove_stale_temporaries).
//
// Every live temporary is also on a list, so that an interrupted process
// (SIGINT, SIGTERM) can remove them all before it exits: see
// remove_temporaries_on_signals().

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace base {

// An open folder that outputs are made in.
class Folder {
public:
    // Opens `path` as the caller names it (e.g. --out), creating it and its
    // parents when `create`. Throws std::runtime_error naming it.
    explicit Folder(const std::filesystem::path& path, bool create = false);
    // The subfolder `name` of `parent` (e.g. thumbs/), created when missing;
    // a symlink or file standing at that name is replaced by a new folder,
    // never followed.
    Folder(const Folder& parent, const std::string& name);
    // The folder that file `path` is (to be) in, opened; the error names `path`.
    static Folder of(const std::filesystem::path& path);
    // The existing subfolder `name` of `parent`, for reading: none when
    // nothing is there or what is there is not a folder (a symlink to one
    // is not followed).
    static std::optional<Folder> inside(const Folder& parent, const std::string& name);

    int fd() const { return handle_->fd; }
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
    Folder(int fd, std::filesystem::path path);
    struct Handle {
        explicit Handle(int descriptor) : fd(descriptor) {}
        Handle(const Handle&) = delete;
        Handle& operator=(const Handle&) = delete;
        ~Handle();
        int fd;
    };
    std::shared_ptr<Handle> handle_;
    std::filesystem::path path_;
};

// A file being written: created under a fresh temporary name, open for
// reading and writing, and put in place by commit().
class AtomicFile {
public:
    enum class Commit {
        with_group,  // commit() waits for this thread's CommitGroup if there is one
        now,         // commit() renames at once (a file inside a temporary folder)
    };
    AtomicFile(Folder folder, std::string name, Commit when = Commit::with_group);
    // The same, for a path whose folder is the caller's (tests, benchmarks).
    explicit AtomicFile(const std::filesystem::path& final_path);
    ~AtomicFile();  // removes the temporary unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    int fd() const { return fd_; }  // the temporary, O_RDWR; -1 once taken or closed
    // The temporary as a stdio stream that the caller then owns and must
    // fclose (checking the result) before commit().
    std::FILE* take_stream();
    std::filesystem::path final_path() const { return folder_ / name_; }
    const Folder& folder() const { return folder_; }
    const std::string& temp_name() const { return temp_; }
    // Closes the file (a full disk may show only then) and renames it over
    // the final name; throws std::runtime_error naming the final path.
    void commit();

private:
    void close_checked();
    Folder folder_;
    std::string name_, temp_;
    int fd_ = -1;
    Commit when_;
    bool committed_ = false;
};

// The same for a folder of files (a PNG sequence): filled under a temporary
// name, then put in place of the final folder at commit(), the old one
// removed. A symlink at the final name is replaced, never followed.
class AtomicDir {
public:
    AtomicDir(const Folder& parent, std::string name);  // creates the temporary folder, exclusively
    ~AtomicDir();                                        // removes it and its files unless committed
    AtomicDir(const AtomicDir&) = delete;
    AtomicDir& operator=(const AtomicDir&) = delete;

    const Folder& folder() const { return *inside_; }  // the temporary folder, to fill
    void commit();

private:
    Folder parent_;
    std::string name_, temp_;
    std::unique_ptr<Folder> inside_;
    bool committed_ = false;
};

// While a CommitGroup lives on a thread, commit() of the AtomicFiles and
// AtomicDirs made on that thread is deferred to the group's commit(), which
// puts them all in place together or none of them: it first checks that
// each final name can take its output (a folder standing where a file goes
// fails), then moves each old output aside and the new one in; if any step
// fails, every step done is undone, so the old outputs stand as they were,
// and the error names the path. A signal waits for it to finish. Destroyed
// without commit(), it removes every deferred temporary.
class CommitGroup {
public:
    CommitGroup();
    ~CommitGroup();
    CommitGroup(const CommitGroup&) = delete;
    CommitGroup& operator=(const CommitGroup&) = delete;
    void commit();  // throws std::runtime_error naming the file on failure

    struct Move {
        Folder folder;
        std::string from, to;
        bool is_folder;
    };
    void defer(Move move) { moves_.push_back(std::move(move)); }
    static CommitGroup* current();  // this thread's, or nullptr

private:
    std::vector<Move> moves_;
    CommitGroup* outer_;
    bool committed_ = false;
};

// The temporary names of output `name` in `folder` left by processes that
// are gone: call only while holding the lock that every writer of `name`
// holds (app::FigureLock), so that none of them can be live. Returns how many
// were removed.
int remove_stale_temporaries(const Folder& folder, const std::vector<std::string>& names);

// Removes `name` in `folder`: a file or symlink, or a folder and everything
// in it, never following a symlink. Returns false if nothing was there.
bool remove_at(const Folder& folder, const std::string& name);

// folder/name opened for reading only if it is a regular file of its own:
// never through a symlink (O_NOFOLLOW), and without waiting on a FIFO or a
// device (O_NONBLOCK, then fstat on the descriptor), so a FIFO planted at a
// name cannot hang the reader. Returns the descriptor (close-on-exec,
// blocking again), or -1 with errno set (ELOOP for a symlink, EINVAL for
// what is not a regular file).
int open_regular_at(const Folder& folder, const std::string& name);
// Why open_regular_at failed with `err`, in words ("it is not a regular file").
std::string not_opened_reason(int err);

// The regular file folder/name, read without following a symlink; none when
// it is not there, is not a regular file, cannot be read or holds more than
// `max_bytes`.
std::optional<std::string> read_file_at(const Folder& folder, const std::string& name, std::size_t max_bytes);

// Writes bytes to folder/name atomically; throws std::runtime_error naming
// the file and the system's reason (e.g. "No space left on device").
void write_file_atomically(const Folder& folder, const std::string& name, const std::string& bytes,
                           AtomicFile::Commit when = AtomicFile::Commit::with_group);
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

// For a command's main(), before it starts any thread: SIGINT, SIGTERM and
// SIGHUP are blocked in every thread and taken by one waiting thread, which
// removes every live temporary file and folder, says so on stderr and ends
// the process with 128 + the signal's number (130 for SIGINT, 143 for
// SIGTERM). Finished outputs and earlier files are never touched.
void remove_temporaries_on_signals();
// The same removal, now, for a process about to end abnormally (an
// exception nothing can report): never throws.
void remove_temporaries_now() noexcept;
// Puts another name (e.g. a lock file) on the list removed at a signal, and takes it off.
void remove_on_signal(const Folder& folder, const std::string& name);
void keep_on_signal(const Folder& folder, const std::string& name);

}  // namespace base
