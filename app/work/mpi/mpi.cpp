// figgen's MPI module: the calls app/work/mpi/api.hpp lists, on Open MPI.
// Messages are bytes (MPI_BYTE), fewer than 2^31 of them: the program
// checks a part's size before it sends it.
// The C API only: the program needs none of the deprecated C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

#include <climits>
#include <cstdio>
#include <cstring>

#include "app/work/mpi/api.hpp"

namespace {

int init(int* rank, int* size, char* error, int error_size) {
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS) {
        std::snprintf(error, static_cast<std::size_t>(error_size), "MPI_Init_thread failed");
        return 1;
    }
    if (provided < MPI_THREAD_SERIALIZED) {
        std::snprintf(error, static_cast<std::size_t>(error_size),
                      "this MPI gives thread level %d, figgen needs MPI_THREAD_SERIALIZED (%d)", provided,
                      MPI_THREAD_SERIALIZED);
        MPI_Finalize();
        return 1;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
    return 0;
}

// Messages of figgen are far below 2 GiB (a part is at most a few MiB),
// which the callers check; counts are ints.
int count_of(long long bytes) {
    if (bytes < 0 || bytes > INT_MAX) MPI_Abort(MPI_COMM_WORLD, 1);
    return static_cast<int>(bytes);
}

void broadcast(void* data, long long bytes) {
    MPI_Bcast(data, count_of(bytes), MPI_BYTE, 0, MPI_COMM_WORLD);
}

void send(int to, int tag, const void* data, long long bytes) {
    MPI_Send(data, count_of(bytes), MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

int probe(int from, int tag, int* source, int* found_tag, long long* bytes) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(from < 0 ? MPI_ANY_SOURCE : from, tag < 0 ? MPI_ANY_TAG : tag, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return 0;
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    *source = status.MPI_SOURCE;
    *found_tag = status.MPI_TAG;
    *bytes = count;
    return 1;
}

void receive(int from, int tag, void* data, long long bytes) {
    MPI_Recv(data, count_of(bytes), MPI_BYTE, from, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

void abort_job(int status) {
    MPI_Abort(MPI_COMM_WORLD, status);
}

void finalize() {
    MPI_Finalize();
}

const app::mpi::Api api = {app::mpi::api_version, init, broadcast, send, probe, receive, abort_job, finalize};

}  // namespace

extern "C" const app::mpi::Api* figgen_mpi_api() {
    return &api;
}
