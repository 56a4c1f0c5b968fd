#pragma once
// The parts store: every finished work item kept as a part, written
// atomically into the figure's parts folder beside its outputs,
// "<out>/<id>.parts/":
//   manifest.json       figgen's version, the figure, the hash of what the
//                       items depend on (scene, seed, [params]) and the
//                       items' names;
//   item-000017.cbor    item 17's result (CBOR), with its index, name, the
//                       manifest's SHA-256 and the result's (result_of_part).
// A run that finds parts with the same manifest computes only the items
// that are missing (a resume); parts with another manifest are never used.
// app/work/schedule.hpp decides which items run where.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "base/atomic_file.hpp"
#include "description/description.hpp"
#include "scenes/work_items.hpp"

namespace app {

// A part as Parts::load found it.
struct Part {
    enum class State { absent, sound, damaged };
    State state = State::absent;
    nlohmann::json result;          // sound: the item's result, checked
    std::string problem;  // damaged: what is wrong, after "<folder>/item-000017.cbor (tile 17) "
};


// A figure's parts folder: its manifest and one file per finished item.
// A part is the CBOR map {item, name, manifest_sha256, result_sha256,
// result}: its result as CBOR bytes of their own and their SHA-256, so that
// a part changed since it was written is told from one that was not; the
// manifest's hash ties it to this figure, settings and figgen.
class Parts {
public:
    // The parts folder of `d` in `out`, made when missing. Parts of another
    // manifest there are stale: they are removed, and the run says so.
    static Parts in_output(const base::Folder& out, const description::Description& d, const scenes::WorkItems& items);

    // The parts a merge was given with --from: the folder itself or the
    // output folder that holds it (a real folder there, not a symlink);
    // refused (UsageError) unless its manifest is this run's.
    static Parts given(const std::filesystem::path& path, const description::Description& d,
                       const scenes::WorkItems& items);

    // Item `item`'s part: absent, sound (its result checked by the scene)
    // or damaged (and why).
    Part load(int item) const;
    // Whether a regular file stands at item `item`'s part (not yet whether it is sound).
    bool has(int item) const;
    // Puts item `item`'s part in place at once, not with the figure's
    // files: a run killed before the figure is written keeps it.
    void store(int item, const nlohmann::json& result) const;
    // "<folder>/item-000017.cbor (tile 17)": what messages call a part.
    std::string named(int item) const;
    const base::Folder& folder() const { return folder_; }

private:
    Parts(base::Folder folder, const scenes::WorkItems& items, nlohmann::json manifest);
    // The manifest, none when there is none; `problem` says why one that is
    // there cannot be read.
    std::optional<nlohmann::json> read_manifest(std::string& problem) const;

    base::Folder folder_;
    const scenes::WorkItems& items_;
    nlohmann::json manifest_;
    std::string manifest_sha256_;
    double max_part_bytes_;
};

// What a merge says of a damaged part (bad input: exit 2).
description::UsageError damaged_part(const Parts& parts, int item, const Part& part);

// A resume's use of item `item`'s part: its result when sound; a damaged
// part is said once and computed again (its new part replaces it).
std::optional<nlohmann::json> kept_result(const Parts& parts, const std::string& id, int item);

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

// Removes figure `id`'s parts folder from `folder` (once its figure is in place).
void remove_parts(const base::Folder& folder, const std::string& id);

}  // namespace app
