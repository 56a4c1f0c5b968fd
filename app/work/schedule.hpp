#pragma once
// Running a figure's work items (scenes/work_items.hpp): on this process's
// threads, over the ranks of an MPI job, as one shard of a job array, or
// not at all (figgen merge, from the parts that shards wrote).
//
// Every finished item is kept as a part (app/work/parts.hpp, the parts
// store); a render removes the parts folder once the figure is in place, a
// shard keeps it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "app/work/bounded_json.hpp"
#include "app/work/cluster.hpp"
#include "app/work/parts.hpp"
#include "base/atomic_file.hpp"
#include "description/description.hpp"
#include "scenes/output.hpp"
#include "scenes/work_items.hpp"

namespace app {

// How the ranks of an MPI job share the items: dynamic (rank 0 hands out
// the next item to whichever rank asks) or fixed (the i-th missing item to
// rank i mod N, `--schedule static`). The results are the same bits.
enum class Schedule { dynamic, fixed };

struct WorkOptions {
    int shard = 0, shards = 0;                      // --shard K/N (1 <= K <= N); 0: not a shard
    std::vector<std::filesystem::path> merge_from;  // figgen merge --from: read, never computed
    Schedule schedule = Schedule::dynamic;
    int threads = 1;             // items run at once in this process
    Cluster* cluster = nullptr;  // the MPI job, when an MPI launcher started figgen

    bool merging() const { return !merge_from.empty(); }
};

// For figgen merge, before anything is created: every --from folder holds
// parts of this very figure, settings and figgen (its manifest), and
// together they hold every item. UsageError naming the folder otherwise.
void check_merge_sources(const description::Description& d, const scenes::WorkItems& items, const WorkOptions& options);

// Every item's result in item order, for rank 0 or a lone process: the parts
// already in `folder`'s parts folder (or, merging, in the --from folders),
// the rest computed here and on the other ranks, each kept as a part as it
// finishes. Throws std::runtime_error for an item that failed, naming the
// rank (in an MPI job), the item and the reason; UsageError for parts that
// a merge cannot use.
std::vector<nlohmann::json> run_work(const description::Description& d, const scenes::WorkItems& items,
                                     const base::Folder& folder, const WorkOptions& options,
                                     scenes::Progress& progress);

// --shard K/N: computes the shard's items (item i when i mod N = K - 1) that
// its parts folder lacks, keeping each as a part. Returns how many it computed.
int run_shard(const description::Description& d, const scenes::WorkItems& items, const base::Folder& folder,
              const WorkOptions& options, scenes::Progress& progress);

// A rank other than 0: runs the items rank 0 gives it for figure `d`, and
// sends rank 0 each result, or the first failure.
void serve_work(const description::Description& d, const scenes::WorkItems& items, const WorkOptions& options);


}  // namespace app
