#include "render/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace render {

AtomicFile::AtomicFile(std::filesystem::path final_path) : final_(std::move(final_path)) {
    // Same folder as the final file, so the rename never crosses filesystems;
    // the pid keeps parallel `make -j` renders of different figures apart.
    temp_ = final_;
    temp_ += ".tmp-" + std::to_string(::getpid());
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        std::error_code ignored;
        std::filesystem::remove(temp_, ignored);
    }
}

void AtomicFile::commit() {
    std::error_code ec;
    std::filesystem::rename(temp_, final_, ec);
    if (ec) throw std::runtime_error("cannot write " + final_.string() + ": " + ec.message());
    committed_ = true;
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

}  // namespace render
