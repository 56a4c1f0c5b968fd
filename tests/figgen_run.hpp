#pragma once
// Running the figgen command from a test, as a user would: its exit status
// and everything it printed. Only for the test binary (FIGGEN_EXE).

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

namespace testkit {

struct Run {
    int status = -1;     // exit status, -1 if it did not exit normally
    std::string output;  // stdout and stderr together
    int lines() const {
        int n = 0;
        for (char c : output) n += c == '\n';
        return n;
    }
};

// Any shell command, stdout and stderr together.
inline Run run_command(const std::string& command) {
    Run run;
    std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    REQUIRE(pipe != nullptr);
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    const int raw = ::pclose(pipe);
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return run;
}

// Runs `figgen args` with the child's environment changed by `assignments`
// ("OMP_NUM_THREADS=2", through env(1); empty: unchanged).
inline Run figgen_env(const std::string& assignments, const std::string& args) {
    std::string command;
    if (!assignments.empty()) command.append("env ").append(assignments).append(" ");
    return run_command(command.append(FIGGEN_EXE).append(" ").append(args));
}

// Runs `figgen args` as a user would: its exit status and everything it printed.
inline Run figgen(const std::string& args) { return figgen_env("", args); }

// A file's bytes, and a file made of `text`.
inline std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
inline void spill(const std::filesystem::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
}

// `count` threads spinning until destroyed: a machine busy with other work.
struct CpuHog {
    explicit CpuHog(int count) {
        for (int i = 0; i < count; ++i)
            threads.emplace_back([this] {
                volatile unsigned long n = 0;
                while (!stop.load(std::memory_order_relaxed)) n = n + 1;
            });
    }
    ~CpuHog() {
        stop = true;
        for (std::thread& t : threads) t.join();
    }
    CpuHog(const CpuHog&) = delete;
    CpuHog& operator=(const CpuHog&) = delete;
    std::atomic<bool> stop{false};
    std::vector<std::thread> threads;
};

// A fresh folder under the test artifacts, private to this process: ctest
// runs test cases side by side, and two of them may render the same figure.
inline std::filesystem::path fresh_dir(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(FIGGEN_TEST_ARTIFACT_DIR) / "cli" / (name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// Renders figure `id` small and without video through the command; returns its metadata.
inline nlohmann::json render_json(const std::string& id, const std::string& extra = "") {
    const std::filesystem::path out = fresh_dir("json-" + id);
    const Run run = figgen("render " + id + " --no-video --scale 0.3 --out " + out.string() + " " + extra);
    INFO(run.output);
    REQUIRE(run.status == 0);
    std::ifstream in(out / (id + ".json"));
    return nlohmann::json::parse(in);
}

}  // namespace testkit
