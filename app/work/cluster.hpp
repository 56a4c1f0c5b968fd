#pragma once
// The MPI job a figgen process is one rank of, when an MPI launcher
// (mpirun, or srun with PMIx) started it. figgen links no MPI library: the
// job is joined through figgen's MPI module (app/work/mpi/), opened at run time
// only in a process that a launcher started, and only once every input is
// accepted. A process started any other way never loads MPI.

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace app {

// Started by an MPI launcher: Open MPI's and PMIx's variables in the environment.
bool launched_by_mpi();
// This process's rank as the launcher's environment gives it (0 when not
// launched by one): for messages before the job is joined.
int launcher_rank();
// Whether another process, rank 0 of a real launch, says what every rank
// found in the inputs: this rank is not 0 and the launcher's environment is
// whole (a PMIx namespace, and PMIx's rank agreeing with Open MPI's). A
// faked or partial environment (OMPI_COMM_WORLD_RANK=1 alone) has no rank 0
// to say it, so the process says it itself.
bool rank_zero_reports();
// How many ranks the launcher started on this node (1 when not launched by one).
int launcher_local_size();

class Cluster {
public:
    // Joins the job (MPI_Init_thread, serialized calls); throws
    // std::runtime_error naming what is missing (the module, Open MPI).
    static std::unique_ptr<Cluster> join();
    ~Cluster();  // leaves the job (MPI_Finalize)
    Cluster(const Cluster&) = delete;
    Cluster& operator=(const Cluster&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }

    using Bytes = std::vector<std::uint8_t>;
    // Rank 0's `bytes` to every rank (a collective: every rank calls it).
    void broadcast(Bytes& bytes);
    void send(int to, int tag, const Bytes& bytes);
    struct Message {
        int from = 0, tag = 0;
        Bytes bytes;
    };
    // A message that has arrived (from `from`, or any rank if -1; with
    // `tag`, or any if -1), taken; none if nothing waits. Never blocks.
    std::optional<Message> poll(int from = -1, int tag = -1);
    // The same, waiting for it (polling with short sleeps: a waiting rank
    // does not spin on a core another rank computes on).
    Message wait(int from = -1, int tag = -1);
    // Ends every rank of the job: the error is already said.
    [[noreturn]] void abort(int status);

private:
    Cluster() = default;
    struct Module;
    const Module* module_ = nullptr;
    int rank_ = 0, size_ = 1;
    std::mutex calls_;  // one MPI call at a time (MPI_THREAD_SERIALIZED)
};

}  // namespace app
