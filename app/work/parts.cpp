#include "app/work/parts.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <utility>

#include "app/work/bounded_json.hpp"
#include "app/work/figure_lock.hpp"
#include "base/digest.hpp"
#include "base/version.hpp"
#include "description/plain_name.hpp"

namespace app {

using description::UsageError;
using nlohmann::json;

namespace {

constexpr const char* parts_format = "figgen-parts-2";
constexpr std::size_t manifest_max_bytes = 64u << 20;

std::string part_name(int item) {
    char name[32];
    std::snprintf(name, sizeof name, "item-%06d.cbor", item);
    return name;
}

// What every process of a run must agree on before it uses a part.
json manifest_of(const description::Description& d, const scenes::WorkItems& items) {
    json names = json::array();
    for (int i = 0; i < items.item_count(); ++i) names.push_back(items.item_name(i));
    return {{"format", parts_format},
            {"figgen", base::version()},
            {"figure", d.id},
            {"description_sha256", work_hash(d, items)},
            {"items", names}};
}

std::string sha256_of(const std::string& text) {
    return base::sha256_hex(text.data(), text.size());
}

// The manifest's value of `key` for a message: its JSON, shortened.
std::string shown_value(const json& manifest, const char* key) {
    const auto it = manifest.find(key);
    return it == manifest.end() ? "none" : description::printable(it->dump(), 80);
}

}  // namespace

Parts::Parts(base::Folder folder, const scenes::WorkItems& items, json manifest)
    : folder_(std::move(folder)),
      items_(items),
      manifest_(std::move(manifest)),
      manifest_sha256_(sha256_of(manifest_.dump())),
      max_part_bytes_(items.item_bytes() + 65536) {}

Parts Parts::in_output(const base::Folder& out, const description::Description& d, const scenes::WorkItems& items) {
    // Shards sharing an output folder may start together: one at a time checks the folder.
    const FigureLock turn(out, parts_name(d.id));
    Parts parts(base::Folder(out, parts_name(d.id)), items, manifest_of(d, items));
    std::string problem;
    const std::optional<json> found = parts.read_manifest(problem);
    if (found != parts.manifest_) {
        // Whatever is there (parts of another manifest, of a damaged one, or of none) is never used.
        if (found || !problem.empty())
            std::fprintf(stderr, "figgen: %s: the parts in %s are of another description or figgen%s; computing anew\n",
                         d.id.c_str(), description::printable(parts.folder_.path().string()).c_str(),
                         problem.empty() ? "" : (" (its manifest " + problem + ")").c_str());
        base::remove_at(out, parts_name(d.id));
        parts.folder_ = base::Folder(out, parts_name(d.id));
        base::write_file_atomically(parts.folder_, "manifest.json", parts.manifest_.dump(1) + "\n",
                                    base::AtomicFile::Commit::now);
    }
    return parts;
}

Parts Parts::given(const std::filesystem::path& path, const description::Description& d,
                   const scenes::WorkItems& items) {
    const std::string option = "--from " + description::printable(path.string());
    const std::string allowed = "allowed: a parts folder (" + parts_name(d.id) +
                                ") or the --out folder of a render --shard that holds one";
    std::optional<base::Folder> folder;
    try {
        const base::Folder named(path);
        struct stat st {};
        if (::fstatat(named.fd(), "manifest.json", &st, AT_SYMLINK_NOFOLLOW) == 0)
            folder = named;  // a parts folder: its manifest is read (and refused) below
        else
            folder = base::Folder::inside(named, parts_name(d.id));
    } catch (const std::runtime_error& e) {
        throw UsageError(option + ": " + e.what() + "; " + allowed);
    }
    if (!folder)
        throw UsageError(option + " holds no parts manifest and no folder " + parts_name(d.id) +
                         " (a symlink is not followed); " + allowed);
    Parts parts(*folder, items, manifest_of(d, items));
    std::string problem;
    const std::optional<json> found = parts.read_manifest(problem);
    if (!problem.empty())
        throw UsageError(option + ": its parts manifest (manifest.json) " + problem + "; allowed: the " +
                         parts_name(d.id) + " folder a render --shard wrote");
    if (!found)
        throw UsageError(option + " has no parts manifest (manifest.json); allowed: the " + parts_name(d.id) +
                         " folder a render --shard wrote");
    for (const char* key : {"format", "figure", "figgen", "description_sha256", "items"}) {
        const auto it = found->find(key);
        if (it == found->end() || *it != parts.manifest_[key])
            throw UsageError(option + ": its parts are of another " +
                             (std::string(key) == "figure"               ? "figure"
                              : std::string(key) == "figgen"             ? "figgen version"
                              : std::string(key) == "description_sha256" ? "description, seed or --set"
                              : std::string(key) == "format"             ? "format"
                                                                         : "item list") +
                             " (manifest " + key + " " + shown_value(*found, key) + ", this run's " +
                             shown_value(parts.manifest_, key) + "); allowed: parts of this same figure, settings and figgen");
    }
    return parts;
}

Part Parts::load(int item) const {
    if (!has(item)) return {};
    const auto damaged = [](std::string problem) { return Part{Part::State::damaged, json(), std::move(problem)}; };
    const std::optional<std::string> bytes =
        base::read_file_at(folder_, part_name(item), static_cast<std::size_t>(max_part_bytes_));
    if (!bytes)
        return damaged("cannot be read or holds more than the " + std::to_string(std::llround(max_part_bytes_)) +
                       " bytes its item's result takes");
    try {
        return {Part::State::sound, result_of_part(*bytes, item, items_, manifest_sha256_), {}};
    } catch (const MalformedData& e) {
        return damaged(e.what());
    }
}

bool Parts::has(int item) const {
    struct stat st {};
    return ::fstatat(folder_.fd(), part_name(item).c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

void Parts::store(int item, const json& result) const {
    // Put in place at once, not with the figure's files: a run killed
    // before the figure is written keeps it.
    base::write_file_atomically(folder_, part_name(item), part_bytes(item, result, items_, manifest_sha256_),
                                base::AtomicFile::Commit::now);
}

std::string Parts::named(int item) const {
    return description::printable((folder_ / part_name(item)).string()) + " (" + items_.item_name(item) + ")";
}

// The manifest, none when there is none; `problem` says why one that is
// there cannot be read.
std::optional<json> Parts::read_manifest(std::string& problem) const {
    struct stat st {};
    if (::fstatat(folder_.fd(), "manifest.json", &st, AT_SYMLINK_NOFOLLOW) != 0) return std::nullopt;
    const std::optional<std::string> text = base::read_file_at(folder_, "manifest.json", manifest_max_bytes);
    if (!text) {
        problem = "is not a regular file of at most " + std::to_string(manifest_max_bytes >> 20) + " MiB";
        return std::nullopt;
    }
    try {
        return app::json_bounded(*text);
    } catch (const MalformedData& e) {
        problem = e.what();
        return std::nullopt;
    }
}


// What a merge says of a damaged part (bad input: exit 2).
UsageError damaged_part(const Parts& parts, int item, const Part& part) {
    return UsageError("--from: the part " + parts.named(item) + " " + part.problem +
                      "; allowed: the parts a render --shard of this figure wrote, unchanged (render that shard again)");
}

// A resume's use of item `item`'s part: its result when sound; a damaged
// part is said once and computed again (its new part replaces it).
std::optional<json> kept_result(const Parts& parts, const std::string& id, int item) {
    Part part = parts.load(item);
    if (part.state == Part::State::sound) return std::move(part.result);
    if (part.state == Part::State::damaged)
        std::fprintf(stderr, "figgen: %s: the part %s %s; computing it again\n", id.c_str(), parts.named(item).c_str(),
                     part.problem.c_str());
    return std::nullopt;
}


json result_of_part(std::string_view bytes, int item, const scenes::WorkItems& items,
                    const std::string& manifest_sha256) {
    const json part = cbor_bounded(bytes);
    if (!part.is_object()) throw MalformedData("is not a map of keys");
    const auto field = [&](const char* key) -> const json* {
        const auto it = part.find(key);
        return it == part.end() ? nullptr : &*it;
    };
    const json *index = field("item"), *name = field("name"), *manifest = field("manifest_sha256"),
               *hash = field("result_sha256"), *result = field("result");
    if (!index || !index->is_number_unsigned() || index->get<std::uint64_t>() != static_cast<std::uint64_t>(item))
        throw MalformedData("is not the part of item " + std::to_string(item));
    if (!name || *name != items.item_name(item)) throw MalformedData("is named for another item");
    if (!manifest || *manifest != manifest_sha256)
        throw MalformedData("was written for another manifest (figure, settings or figgen)");
    if (!result || !result->is_binary() || !hash || !hash->is_string())
        throw MalformedData("lacks its result or the result's SHA-256");
    const std::vector<std::uint8_t>& result_bytes = result->get_binary();
    if (base::sha256_hex(result_bytes.data(), result_bytes.size()) != hash->get_ref<const std::string&>())
        throw MalformedData("has a result that does not match its SHA-256 (changed since it was written)");
    json decoded;
    try {
        decoded = cbor_bounded(std::string_view(reinterpret_cast<const char*>(result_bytes.data()), result_bytes.size()));
    } catch (const MalformedData& e) {
        throw MalformedData("has a result that " + std::string(e.what()));
    }
    try {
        items.check_result(item, decoded);
    } catch (const std::invalid_argument& e) {
        throw MalformedData("has a result its item cannot give: " + std::string(e.what()));
    }
    return decoded;
}

std::string part_bytes(int item, const json& result, const scenes::WorkItems& items,
                       const std::string& manifest_sha256) {
    std::vector<std::uint8_t> result_bytes = json::to_cbor(result);
    const std::string hash = base::sha256_hex(result_bytes.data(), result_bytes.size());
    // Moved, not copied: a result is as many copies of its numbers as the memory estimates count.
    const std::vector<std::uint8_t> bytes = json::to_cbor({{"item", item},
                                                           {"name", items.item_name(item)},
                                                           {"manifest_sha256", manifest_sha256},
                                                           {"result_sha256", hash},
                                                           {"result", json::binary(std::move(result_bytes))}});
    return std::string(bytes.begin(), bytes.end());
}

std::string parts_name(const std::string& id) {
    return id + ".parts";
}

std::string work_hash(const description::Description& d, const scenes::WorkItems& items) {
    std::ostringstream params;
    params << toml::json_formatter{d.params};
    const std::string text = std::string(base::version()) + "\n" + d.scene + "\n" + std::to_string(d.seed) + "\n" +
                             params.str() + "\n" + items.depends_on();
    return base::sha256_hex(text.data(), text.size());
}

void remove_parts(const base::Folder& folder, const std::string& id) {
    base::remove_at(folder, parts_name(id));
}

}  // namespace app
