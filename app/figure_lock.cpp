#include "app/figure_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <system_error>

#include "render/atomic_file.hpp"

namespace app {

FigureLock::FigureLock(const std::filesystem::path& dir, const std::string& id) {
    struct stat folder {};
    if (::stat(dir.c_str(), &folder) != 0) return;  // the caller has made it; without it there is nothing to share
    std::error_code ec;
    name_ = std::filesystem::temp_directory_path(ec) / ("figgen-" + std::to_string(folder.st_dev) + "-" +
                                                       std::to_string(folder.st_ino) + "-" + id + ".lock");
    if (ec) return;
    for (bool told = false;;) {
        fd_ = ::open(name_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
        if (fd_ < 0) return;  // no temporary folder: no turns, each file is still written whole
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            if (!told)
                std::fprintf(stderr, "figgen: waiting for another figgen writing %s into %s\n", id.c_str(),
                             dir.c_str());
            told = true;
            ::flock(fd_, LOCK_EX);
        }
        struct stat held {}, named {};
        if (::fstat(fd_, &held) == 0 && ::stat(name_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
            held.st_dev == named.st_dev)
        {
            render::remove_on_signal(name_);
            return;  // the lock is ours and still the one the name leads to
        }
        ::close(fd_);
    }
}

FigureLock::~FigureLock() {
    if (fd_ < 0) return;
    ::unlink(name_.c_str());  // while still held: see the constructor
    render::keep_on_signal(name_);
    ::close(fd_);
}

}  // namespace app
