#include "app/work/figure_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace app {

FigureLock::FigureLock(const base::Folder& folder, const std::string& id) : folder_(folder), name_("." + id + "~lock") {
    for (bool told = false;;) {
        fd_ = ::openat(folder_.fd(), name_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd_ < 0 && errno == ELOOP) {
            ::unlinkat(folder_.fd(), name_.c_str(), 0);  // a symlink planted at the lock's name: never followed
            continue;
        }
        if (fd_ < 0)
            throw std::runtime_error("cannot write into " + folder_.path().string() + ": " + std::strerror(errno));
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            if (!told)
                std::fprintf(stderr, "figgen: waiting for another figgen writing %s into %s\n", id.c_str(),
                             folder_.path().c_str());
            told = true;
            ::flock(fd_, LOCK_EX);
        }
        struct stat held {}, named {};
        if (::fstat(fd_, &held) == 0 && ::fstatat(folder_.fd(), name_.c_str(), &named, AT_SYMLINK_NOFOLLOW) == 0 &&
            held.st_ino == named.st_ino && held.st_dev == named.st_dev)
        {
            base::remove_on_signal(folder_, name_);
            return;  // the lock is ours and still the one the name leads to
        }
        ::close(fd_);
    }
}

FigureLock::~FigureLock() {
    ::unlinkat(folder_.fd(), name_.c_str(), 0);  // while still held: see the constructor
    base::keep_on_signal(folder_, name_);
    ::close(fd_);
}

}  // namespace app
