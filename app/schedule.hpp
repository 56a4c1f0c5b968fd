#pragma once
// Running a figure's work items (scenes/work_items.hpp): on this process's
// threads, over the ranks of an MPI job, as one shard of a job array, or
// not at all (figgen merge, from the parts that shards wrote).
//
// Every finished item is kept as a part, written atomically into the
// figure's parts folder beside its outputs, "<out>/<id>.parts/":
//   manifest.json       figgen's version, the figure, the hash of what the
//                       items depend on (scene, seed, [params]) and the
//                       items' names;
//   item-000017.cbor    item 17's result (CBOR), with its index, name, the
//                       manifest's SHA-256 and the result's (result_of_part).
// A run that finds parts with the same manifest computes only the items
// that are missing (a resume); parts with another manifest are never used.
// A render removes the folder once the figure is in place; a shard keeps it.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "app/bounded_json.hpp"
#include "app/cluster.hpp"
#include "description/description.hpp"
#include "base/atomic_file.hpp"
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

// "gs-atlas.parts"
std::string parts_name(const std::string& id);

// Item `item`'s result from the bytes of its part, as a merge or a resume
// reads it: a CBOR map {item, name, manifest_sha256, result_sha256, result}
// of this item, of the manifest whose SHA-256 is `manifest_sha256`, whose
// result (CBOR bytes of their own) matches its SHA-256 and passes
// items.check_result. Throws app::MalformedData saying what is wrong, in
// words that follow the part's name.
nlohmann::json result_of_part(std::string_view bytes, int item, const scenes::WorkItems& items,
                              const std::string& manifest_sha256);
// The bytes of item `item`'s part holding `result` (what a run stores).
std::string part_bytes(int item, const nlohmann::json& result, const scenes::WorkItems& items,
                       const std::string& manifest_sha256);
// The hex SHA-256 of what the items' results depend on: the scene, the
// seed, the [params] as read, figgen's version and items.depends_on().
std::string work_hash(const description::Description& d, const scenes::WorkItems& items);

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

// Removes figure `id`'s parts folder from `folder` (once its figure is in place).
void remove_parts(const base::Folder& folder, const std::string& id);

}  // namespace app
