// The rendered folder as the gallery reads it: every file untrusted.

#include "app/gallery/folder.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/gallery/key_numbers.hpp"
#include "app/render/formats.hpp"
#include "app/render/output_files.hpp"
#include "app/work/bounded_json.hpp"
#include "base/atomic_file.hpp"
#include "base/version.hpp"
#include "description/catalog.hpp"
#include "description/plain_name.hpp"
#include "media/png_io.hpp"
#include "media/thumbnail.hpp"
#include "media/video.hpp"

namespace app::gallery {

// The most pixels an image may claim under `max_memory`, at `bytes_per_pixel`.
std::uint64_t max_pixels(std::uint64_t max_memory, double bytes_per_pixel) {
    const double room = static_cast<double>(max_memory) - program_bytes;
    return room <= 0 ? 0 : static_cast<std::uint64_t>(room / bytes_per_pixel);
}

// Why `file` was not read: one line with the size its header claims and
// the memory that would take.
std::string refusal(const std::string& file, const render::ImageTooLarge& e, std::uint64_t max_memory,
                    double bytes_per_pixel) {
    const double needs = program_bytes + bytes_per_pixel * static_cast<double>(e.width) * static_cast<double>(e.height);
    return file + " is not decoded: its header claims " + std::to_string(e.width) + " x " + std::to_string(e.height) +
           " pixels, which would take about " + format_bytes(needs) + " to decode, more than --max-memory " +
           format_bytes(static_cast<double>(max_memory));
}

// What the metadata says, read as untrusted: a missing or mistyped field
// gives the fallback, never an exception.
const nlohmann::json& member(const nlohmann::json& node, const char* key) {
    static const nlohmann::json none;
    if (!node.is_object()) return none;
    const auto found = node.find(key);
    return found == node.end() ? none : *found;
}
std::string text_of(const nlohmann::json& node, const char* key, const std::string& fallback) {
    const nlohmann::json& value = member(node, key);
    return value.is_string() ? value.get<std::string>() : fallback;
}
// A positive integer up to a million (a size, a count), else 0.
int count_of(const nlohmann::json& value) {
    return value.is_number_integer() && value.get<long long>() > 0 && value.get<long long>() <= 1'000'000
               ? static_cast<int>(value.get<long long>())
               : 0;
}
// An index below `limit` (a frame of a film), else -1.
int index_of(const nlohmann::json& value, int limit) {
    return value.is_number_integer() && value.get<long long>() >= 0 && value.get<long long>() < limit
               ? static_cast<int>(value.get<long long>())
               : -1;
}
// Whether `name` in `folder` is a file of its own: not a symlink (which could
// lead out of the folder), not a folder.
bool is_file_in(const base::Folder& folder, const std::string& name) {
    struct stat st {};
    return ::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
}

// A figure's metadata is at most 16 MiB and nests at most 64 levels (the
// catalog's nest 5): the parser stops deeper, so that a hand-made JSON of a
// million nested `[` is refused as it is read, never walked, copied or
// dumped by recursion.
constexpr std::size_t max_metadata_bytes = 16u << 20;
constexpr int max_metadata_depth = most_nesting;

// Whether something other than a regular file (a FIFO, a folder, a
// symlink) stands at `name` in `folder`.
bool is_other_than_file(const base::Folder& folder, const std::string& name) {
    struct stat st {};
    return ::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode);
}

// The metadata folder/name, read as a regular file (no symlink followed, no
// FIFO waited on); null when it is not there or is not JSON, and also when
// it is not a regular file, is too large or nests too deep, which
// `problem` then says.
nlohmann::json read_metadata(const base::Folder& folder, const std::string& name, std::string* problem) {
    const auto refused = [&](const std::string& why) {
        if (problem) *problem = name + " " + why;
        return nullptr;
    };
    struct stat st {};
    if (::fstatat(folder.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) return nullptr;  // not there
    if (!S_ISREG(st.st_mode)) return refused("is not a regular file");
    if (st.st_size > static_cast<off_t>(max_metadata_bytes))
        return refused("holds more than " + std::to_string(max_metadata_bytes >> 20) + " MiB");
    // Read through a descriptor checked again: the name may have changed since.
    const std::optional<std::string> text = base::read_file_at(folder, name, max_metadata_bytes);
    if (!text)
        return refused("could not be read as a regular file of at most " + std::to_string(max_metadata_bytes >> 20) +
                       " MiB");
    try {
        return json_bounded(*text, max_metadata_depth);
    } catch (const MalformedData& e) {
        if (std::string_view(e.what()).rfind("nests", 0) == 0) return refused(e.what());
        return nlohmann::json(nlohmann::json::value_t::discarded);  // not JSON: as before, no card data
    }
}

// The figures in the folder that are not the catalog's: every ID.json
// figgen wrote (an object whose "id" is its file's name, a plain id, and
// which names the figgen that wrote it) beside its ID.png, in name order.
// Names come from the folder's listing, never from a JSON; symlinks are
// passed over, as everywhere in the gallery.
std::vector<std::string> figures_outside(const base::Folder& folder, const std::vector<std::string>& catalog,
                                         std::vector<std::string>& unreadable) {
    std::vector<std::string> ids;
    const int fd = ::openat(folder.fd(), ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return ids;
    DIR* listing = ::fdopendir(fd);
    if (!listing) {
        ::close(fd);
        return ids;
    }
    while (const dirent* entry = ::readdir(listing)) {
        const std::string name = entry->d_name;
        if (name.size() <= 5 || name.compare(name.size() - 5, 5, ".json") != 0) continue;
        const std::string id = name.substr(0, name.size() - 5);
        if (!description::is_plain_id(id) || std::find(catalog.begin(), catalog.end(), id) != catalog.end()) continue;
        if (!is_file_in(folder, name) || !is_file_in(folder, id + ".png")) continue;
        ids.push_back(id);
        if (ids.size() >= max_other_figures) break;
    }
    ::closedir(listing);
    std::sort(ids.begin(), ids.end());
    std::erase_if(ids, [&](const std::string& id) {
        std::string problem;
        const nlohmann::json meta = read_metadata(folder, id + ".json", &problem);
        if (!problem.empty()) unreadable.push_back(id + ": " + problem);
        return !(meta.is_object() && text_of(meta, "id", "") == id && !text_of(meta, "figgen_version", "").empty());
    });
    return ids;
}

}  // namespace app::gallery
