#include "app/work/cluster.hpp"

#include <chrono>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "app/work/mpi/api.hpp"
#include "base/module.hpp"

namespace app {
namespace {

int environment_int(const char* name, int fallback) {
    const char* text = std::getenv(name);
    if (!text || !*text) return fallback;
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    return (*end == '\0' && value >= 0 && value <= INT_MAX) ? static_cast<int>(value) : fallback;
}

}  // namespace

bool launched_by_mpi() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK");
}

int launcher_rank() {
    return environment_int("OMPI_COMM_WORLD_RANK", environment_int("PMIX_RANK", 0));
}

bool rank_zero_reports() {
    const int rank = launcher_rank();
    const char* space = std::getenv("PMIX_NAMESPACE");
    return rank != 0 && space && *space && environment_int("PMIX_RANK", -1) == rank;
}

int launcher_local_size() {
    return std::max(1, environment_int("OMPI_COMM_WORLD_LOCAL_SIZE", 1));
}

struct Cluster::Module : mpi::Api {};

std::unique_ptr<Cluster> Cluster::join() {
#ifndef FIGGEN_MPI_BUILT
    throw std::runtime_error(
        "started by an MPI launcher, but this figgen was built without MPI: install libopenmpi-dev "
        "(scripts/deps.sh) and build again");
#else
    static constexpr base::ModuleSpec spec{FIGGEN_MPI_RELATIVE,
                                           FIGGEN_MPI_BUILT,
                                           "figgen_mpi_api",
                                           mpi::api_version,
                                           "MPI module",
                                           "libopenmpi3 and openmpi-bin (scripts/deps.sh)",
                                           true};
    const base::OpenedModule opened = base::open_module(spec);
    if (!opened.api) throw std::runtime_error(opened.error);
    const auto* api = static_cast<const mpi::Api*>(opened.api);
    std::unique_ptr<Cluster> cluster(new Cluster);
    cluster->module_ = static_cast<const Module*>(api);
    char error[256] = {};
    if (api->init(&cluster->rank_, &cluster->size_, error, sizeof error) != 0)
        throw std::runtime_error(std::string("cannot join the MPI job: ") + error);
    return cluster;
#endif
}

Cluster::~Cluster() {
    if (module_) module_->finalize();
}

void Cluster::broadcast(Bytes& bytes) {
    std::lock_guard<std::mutex> hold(calls_);
    long long size = static_cast<long long>(bytes.size());
    module_->broadcast(&size, sizeof size);
    bytes.resize(static_cast<std::size_t>(size));
    if (size > 0) module_->broadcast(bytes.data(), size);
}

void Cluster::send(int to, int tag, const Bytes& bytes) {
    if (bytes.size() > static_cast<std::size_t>(INT_MAX))
        throw std::runtime_error("a message of " + std::to_string(bytes.size()) + " bytes is beyond MPI's 2 GiB");
    std::lock_guard<std::mutex> hold(calls_);
    module_->send(to, tag, bytes.data(), static_cast<long long>(bytes.size()));
}

std::optional<Cluster::Message> Cluster::poll(int from, int tag) {
    std::lock_guard<std::mutex> hold(calls_);
    Message m;
    long long size = 0;
    if (!module_->probe(from, tag, &m.from, &m.tag, &size)) return std::nullopt;
    m.bytes.resize(static_cast<std::size_t>(size));
    module_->receive(m.from, m.tag, m.bytes.data(), size);
    return m;
}

Cluster::Message Cluster::wait(int from, int tag) {
    for (auto pause = std::chrono::microseconds(20);; pause = std::min(pause * 2, std::chrono::microseconds(2000))) {
        if (std::optional<Message> m = poll(from, tag)) return std::move(*m);
        std::this_thread::sleep_for(pause);
    }
}

void Cluster::abort(int status) {
    module_->abort(status);
    std::_Exit(status);  // MPI_Abort does not return; should it, end here all the same
}

}  // namespace app
