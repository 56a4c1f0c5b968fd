#pragma once

#include <string>

#include "base/atomic_file.hpp"

namespace app {

// Two figgen processes rendering the same figure into the same folder take
// turns: otherwise one's PNG could end up beside the other's JSON. The lock
// is the file ".ID~lock" in the output folder itself (hidden, and '~' is in
// no id), held with flock, so whatever TMPDIR each process has they find
// the same one, and it is released when its holder ends, however it ends.
// The holder removes it when done; a waiter that then wins a removed file's
// lock sees that the name no longer leads to it and tries again.
class FigureLock {
public:
    // Waits for the turn of figure `id` in `folder`. Throws std::runtime_error
    // when the lock cannot be made (a folder that cannot be written).
    FigureLock(const base::Folder& folder, const std::string& id);
    ~FigureLock();
    FigureLock(const FigureLock&) = delete;
    FigureLock& operator=(const FigureLock&) = delete;

private:
    base::Folder folder_;
    std::string name_;
    int fd_ = -1;
};

}  // namespace app
