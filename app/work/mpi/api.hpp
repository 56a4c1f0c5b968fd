#pragma once
// What figgen's MPI module (libfiggen_mpi.so, app/work/mpi/mpi.cpp) gives the
// program: a few MPI calls behind plain C types, so that the program
// itself links no MPI library (app/work/cluster.cpp opens the module only in a
// process an MPI launcher started).

namespace app::mpi {

inline constexpr int api_version = 1;

struct Api {
    int version;  // api_version of the module's build
    // MPI_Init_thread asking MPI_THREAD_SERIALIZED; 0 and rank and size, or
    // nonzero with the reason in `error`.
    int (*init)(int* rank, int* size, char* error, int error_size);
    void (*broadcast)(void* data, long long bytes);  // from rank 0, `bytes` the same on every rank
    void (*send)(int to, int tag, const void* data, long long bytes);
    // Whether a message from `from` with `tag` (-1: any) has arrived; if so its source, tag and size.
    int (*probe)(int from, int tag, int* source, int* found_tag, long long* bytes);
    void (*receive)(int from, int tag, void* data, long long bytes);
    void (*abort)(int status);
    void (*finalize)();
};

}  // namespace app::mpi

extern "C" const app::mpi::Api* figgen_mpi_api();
