#pragma once

#include <filesystem>
#include <string>

namespace app {

// Two figgen processes rendering the same figure into the same folder take
// turns: otherwise one's PNG could end up beside the other's JSON. The lock
// is a file in the temporary folder named after the output folder's device
// and inode and the id, so the output folder holds nothing but outputs. The
// holder removes it when done; a waiter that then wins a removed file's lock
// sees that the name no longer leads to it and tries again. flock releases
// it when the process ends, however it ends.
class FigureLock {
public:
    // Waits for the turn of figure `id` in folder `dir` (which exists).
    FigureLock(const std::filesystem::path& dir, const std::string& id);
    ~FigureLock();
    FigureLock(const FigureLock&) = delete;
    FigureLock& operator=(const FigureLock&) = delete;

private:
    std::filesystem::path name_;
    int fd_ = -1;
};

}  // namespace app
