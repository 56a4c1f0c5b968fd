#pragma once
// Every output is written under a temporary name in its final folder and
// renamed over the final name only once complete, so a crash, a full disk or
// an error never leaves a half-written file under the real name.

#include <filesystem>
#include <string>

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

// Writes bytes to `path` atomically; throws std::runtime_error naming the file
// and the system's reason (e.g. "No space left on device").
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

}  // namespace render
