#pragma once
// Every output is written under a temporary name in its final folder and
// renamed over the final name only once complete, so a crash, a full disk or
// an error never leaves a half-written file under the real name.
//
// Every live temporary is also on a list, so that an interrupted process
// (SIGINT, SIGTERM) can remove them all before it exits: see
// remove_temporaries_on_signals().

#include <filesystem>
#include <string>
#include <vector>

namespace render {

class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path final_path);
    ~AtomicFile();  // removes the temporary file unless commit() succeeded
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::filesystem::path& temp_path() const { return temp_; }
    const std::filesystem::path& final_path() const { return final_; }
    void commit();  // renames temp over final; throws std::runtime_error on failure

private:
    std::filesystem::path final_;
    std::filesystem::path temp_;
    bool committed_ = false;
};

// The same for a folder of files (a PNG sequence): filled under a temporary
// name, then put in place of the final folder at commit(), the old one's
// files removed. Between the two renames of commit() the final name is
// briefly absent, never half-filled.
class AtomicDir {
public:
    explicit AtomicDir(std::filesystem::path final_path);  // creates the temporary folder
    ~AtomicDir();                                          // removes it and its files unless committed
    AtomicDir(const AtomicDir&) = delete;
    AtomicDir& operator=(const AtomicDir&) = delete;

    const std::filesystem::path& temp_path() const { return temp_; }
    void commit();

private:
    std::filesystem::path final_;
    std::filesystem::path temp_;
    bool committed_ = false;
};

// While a CommitGroup lives on a thread, commit() of the AtomicFiles and
// AtomicDirs made on that thread is deferred to the group's commit(), which
// puts them all in place at once (in the order they were committed; a
// signal waits for it to finish). A figure's PNG, JSON, MP4 and frames thus
// replace the earlier ones together or not at all: a failure after the MP4
// cannot leave a new MP4 beside the old PNG. Destroyed without commit(),
// it removes every deferred temporary.
class CommitGroup {
public:
    CommitGroup();
    ~CommitGroup();
    CommitGroup(const CommitGroup&) = delete;
    CommitGroup& operator=(const CommitGroup&) = delete;
    void commit();  // throws std::runtime_error naming the file on failure

    struct Move {
        std::filesystem::path from, to;
        bool folder;
    };
    void defer(Move move) { moves_.push_back(std::move(move)); }
    static CommitGroup* current();  // this thread's, or nullptr

private:
    std::vector<Move> moves_;
    CommitGroup* outer_;
    bool committed_ = false;
};

// Writes bytes to `path` atomically; throws std::runtime_error naming the file
// and the system's reason (e.g. "No space left on device").
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

// For a command's main(), before it starts any thread: SIGINT, SIGTERM and
// SIGHUP are blocked in every thread and taken by one waiting thread, which
// removes every live temporary file and folder, says so on stderr and ends
// the process with 128 + the signal's number (130 for SIGINT, 143 for
// SIGTERM). Finished outputs and earlier files are never touched.
void remove_temporaries_on_signals();
// Puts another file (e.g. a lock) on the list removed at a signal, and takes it off.
void remove_on_signal(const std::filesystem::path& path);
void keep_on_signal(const std::filesystem::path& path);

}  // namespace render
