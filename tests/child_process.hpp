#pragma once
// A figgen process started by a test with control over what a plain
// system() cannot give: its working folder, a file size limit (a disk that
// fills up), an unprivileged user (so that a read-only folder is read-only
// even when the tests run as root), and a start that waits for go(), so the
// test can prepare for its pid.

#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

namespace testkit {

struct ChildOptions {
    std::filesystem::path cwd;             // empty: the test's
    rlim_t file_size_limit = 0;            // the largest file it may write; 0: no limit
    rlim_t address_space_limit = 0;        // its largest address space (RLIMIT_AS); 0: no limit
    bool unprivileged = false;             // when the test runs as root, run as nobody (65534)
    std::vector<std::string> environment;  // "NAME=value" set in the child

    static ChildOptions files_up_to(rlim_t bytes) {
        ChildOptions o;
        o.file_size_limit = bytes;
        return o;
    }
    static ChildOptions memory_up_to(rlim_t bytes) {
        ChildOptions o;
        o.address_space_limit = bytes;
        return o;
    }
    static ChildOptions as_nobody() {
        ChildOptions o;
        o.unprivileged = true;
        return o;
    }
    static ChildOptions with_environment(std::vector<std::string> assignments) {
        ChildOptions o;
        o.environment = std::move(assignments);
        return o;
    }
};

class Child {
public:
    // stdout and stderr go to `log`.
    Child(const std::vector<std::string>& args, const std::filesystem::path& log, const ChildOptions& options = {}) {
        int fds[2];
        REQUIRE(::pipe(fds) == 0);
        pid_ = ::fork();
        REQUIRE(pid_ >= 0);
        if (pid_ == 0) {
            ::close(fds[1]);
            char ready;
            if (::read(fds[0], &ready, 1) != 1) ::_exit(99);
            const int err = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
            ::dup2(err, 2);
            ::dup2(err, 1);
            if (!options.cwd.empty() && ::chdir(options.cwd.c_str()) != 0) ::_exit(96);
            for (const std::string& assignment : options.environment)
                ::putenv(const_cast<char*>(assignment.c_str()));
            if (options.file_size_limit > 0) {
                const struct rlimit limit = {options.file_size_limit, options.file_size_limit};
                ::signal(SIGXFSZ, SIG_IGN);  // kept across exec: a write past the limit fails with EFBIG
                if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(97);
            }
            if (options.address_space_limit > 0) {
                const struct rlimit limit = {options.address_space_limit, options.address_space_limit};
                if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(94);
            }
            if (options.unprivileged && ::geteuid() == 0) {
                const gid_t nogroup = 65534;
                if (::setgroups(1, &nogroup) != 0 || ::setgid(65534) != 0 || ::setuid(65534) != 0) ::_exit(95);
            }
            std::vector<char*> argv{const_cast<char*>(FIGGEN_EXE)};
            for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
            argv.push_back(nullptr);
            ::execv(FIGGEN_EXE, argv.data());
            ::_exit(98);
        }
        ::close(fds[0]);
        go_ = fds[1];
    }
    ~Child() {
        if (go_ >= 0) ::close(go_);
        if (pid_ > 0 && !waited_) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, nullptr, 0);
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    pid_t pid() const { return pid_; }
    void go() {
        REQUIRE(::write(go_, "g", 1) == 1);
        ::close(go_);
        go_ = -1;
    }
    int wait() {  // raw wait status
        int status = 0;
        ::waitpid(pid_, &status, 0);
        waited_ = true;
        return status;
    }

private:
    pid_t pid_ = -1;
    int go_ = -1;
    bool waited_ = false;
};

}  // namespace testkit
