#pragma once
// Work items: the independent runs a figure's model splits into (a
// gs-atlas tile, an L of bd-roughness, a block of pc-threshold samples),
// so that they can be spread over threads, MPI ranks or job-array shards
// and kept, each as it finishes, for a run that is resumed.
//
// An item's result depends on the description and the item's index only:
// its random draws come from sim::Random::for_item(seed, item), never from
// a generator shared between items, so the same item gives the same result
// on any thread, rank or shard. The scene combines the results in item
// order (Output::results), so the figure is the same bits however it ran.

#include <nlohmann/json.hpp>
#include <string>

namespace scenes {

class WorkItems {
public:
    virtual ~WorkItems() = default;
    virtual int item_count() const = 0;
    // What an error message calls item `item`: "tile 17 (f = 0.0113, k = 0.0419)".
    virtual std::string item_name(int item) const = 0;
    // Runs item `item` (0 <= item < item_count()); may be called from any
    // thread, several at once. Throws std::runtime_error when its model
    // fails (the message says why; the caller adds the item's name).
    virtual nlohmann::json run_item(int item) const = 0;
    // Checks a result of item `item` read back from a part (a merge or a
    // resume reads parts that anyone could have edited): every key run_item
    // writes is there with its type, every count is the item's, every number
    // is finite and within what the item's run can give. Throws
    // std::invalid_argument saying what is wrong ("b holds -1e+30, outside
    // [-10, 10]"); a result that passes can be drawn without a crash.
    virtual void check_result(int item, const nlohmann::json& result) const = 0;
    // At most how many bytes an item's result takes stored (CBOR), for the
    // disk estimate of the parts kept for a resume.
    virtual double item_bytes() const = 0;
    // At most how many bytes all the results take stored (the parts folder).
    virtual double total_bytes() const { return item_bytes() * item_count(); }
    // What the results depend on beyond the scene, the seed and [params]
    // (which every parts manifest hashes): e.g. a film's size and encoding.
    virtual std::string depends_on() const { return {}; }
};

}  // namespace scenes
