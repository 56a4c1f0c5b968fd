#include "app/work.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/figure_lock.hpp"
#include "app/version.hpp"
#include "description/plain_name.hpp"
#include "render/digest.hpp"

namespace app {

using description::UsageError;
using nlohmann::json;

namespace {

constexpr const char* parts_format = "figgen-parts-1";
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
            {"figgen", version()},
            {"figure", d.id},
            {"description_sha256", work_hash(d, items)},
            {"items", names}};
}

// A figure's parts folder: its manifest and one file per finished item.
class Parts {
public:
    // The parts folder of `d` in `out`, made when missing. Parts of another
    // manifest there are stale: they are removed, and the run says so.
    static Parts in_output(const render::Folder& out, const description::Description& d,
                           const scenes::WorkItems& items) {
        // Shards sharing an output folder may start together: one at a time checks the folder.
        const FigureLock turn(out, parts_name(d.id));
        Parts parts(render::Folder(out, parts_name(d.id)), items, manifest_of(d, items));
        const std::optional<json> found = parts.read_manifest();
        if (found != parts.manifest_) {
            // Whatever is there (parts of another manifest, or of none) is never used.
            if (found)
                std::fprintf(stderr,
                             "figgen: %s: the parts in %s are of another description or figgen; computing anew\n",
                             d.id.c_str(), description::printable(parts.folder_.path().string()).c_str());
            render::remove_at(out, parts_name(d.id));
            parts.folder_ = render::Folder(out, parts_name(d.id));
            render::write_file_atomically(parts.folder_, "manifest.json", parts.manifest_.dump(1) + "\n",
                                          render::AtomicFile::Commit::now);
        }
        return parts;
    }

    // The parts a merge was given with --from: the folder itself or the
    // output folder that holds it; refused (UsageError) unless its manifest
    // is this run's.
    static Parts given(const std::filesystem::path& path, const description::Description& d,
                       const scenes::WorkItems& items) {
        const std::string option = "--from " + path.string();
        std::optional<render::Folder> folder;
        try {
            const render::Folder named(path);
            folder = render::read_file_at(named, "manifest.json", manifest_max_bytes)
                         ? named
                         : render::Folder(path / parts_name(d.id));
        } catch (const std::runtime_error& e) {
            throw UsageError(option + ": " + e.what() + "; allowed: a parts folder (" + parts_name(d.id) +
                             ") or the --out folder of a render --shard that holds one");
        }
        Parts parts(*folder, items, manifest_of(d, items));
        const std::optional<json> found = parts.read_manifest();
        if (!found)
            throw UsageError(option + " has no parts manifest (manifest.json); allowed: the " + parts_name(d.id) +
                             " folder a render --shard wrote");
        for (const char* key : {"format", "figure", "figgen", "description_sha256", "items"})
            if (found->value(key, json()) != parts.manifest_[key])
                throw UsageError(option + ": its parts are of another " +
                                 (std::string(key) == "figure"               ? "figure"
                                  : std::string(key) == "figgen"             ? "figgen version"
                                  : std::string(key) == "description_sha256" ? "description, seed or --set"
                                                                             : "item list") +
                                 " (manifest " + key + " " + description::printable(found->value(key, json()).dump()) +
                                 ", this run's " + description::printable(parts.manifest_[key].dump()) +
                                 "); allowed: parts of this same figure, settings and figgen");
        return parts;
    }

    // Item `item`'s result if its part is here and sound; a part that does
    // not decode, or is of another item, is left out (computed again).
    std::optional<json> load(int item) const {
        const std::optional<std::string> bytes =
            render::read_file_at(folder_, part_name(item), static_cast<std::size_t>(max_part_bytes_));
        if (!bytes) return std::nullopt;
        const json part = json::from_cbor(*bytes, true, false);
        if (part.is_discarded() || !part.is_object() || part.value("item", -1) != item ||
            part.value("name", std::string()) != items_.item_name(item) || !part.contains("result"))
            return std::nullopt;
        return part["result"];
    }

    // Whether item `item`'s part is here (not yet whether it decodes).
    bool has(int item) const {
        struct stat st {};
        return ::fstatat(folder_.fd(), part_name(item).c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
    }

    void store(int item, const json& result) const {
        // Put in place at once, not with the figure's files: a run killed
        // before the figure is written keeps it.
        const std::vector<std::uint8_t> bytes =
            json::to_cbor({{"item", item}, {"name", items_.item_name(item)}, {"result", result}});
        render::write_file_atomically(folder_, part_name(item), std::string(bytes.begin(), bytes.end()),
                                      render::AtomicFile::Commit::now);
    }

    const render::Folder& folder() const { return folder_; }

private:
    Parts(render::Folder folder, const scenes::WorkItems& items, json manifest)
        : folder_(std::move(folder)),
          items_(items),
          manifest_(std::move(manifest)),
          max_part_bytes_(items.item_bytes() + 65536) {}

    std::optional<json> read_manifest() const {
        const std::optional<std::string> text = render::read_file_at(folder_, "manifest.json", manifest_max_bytes);
        if (!text) return std::nullopt;
        json m = json::parse(*text, nullptr, false);
        if (m.is_discarded()) return std::nullopt;
        return m;
    }

    render::Folder folder_;
    const scenes::WorkItems& items_;
    json manifest_;
    double max_part_bytes_;
};

// Runs one item; a failure becomes a message naming it.
json run_one(const description::Description& d, const scenes::WorkItems& items, int item) {
    try {
        return items.run_item(item);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        throw std::runtime_error(d.id + ", " + items.item_name(item) + ": " + e.what());
    }
}

// Runs `next()`'s items on `threads` threads until it gives -1 or an item
// fails; `done(item, result)` is called on the thread that ran it. The first
// failure is rethrown once every thread has stopped.
template <class Next, class Done>
void run_on_threads(int threads, Next&& next, Done&& done) {
    std::mutex failure_lock;
    std::exception_ptr failure;
    std::atomic<bool> failed{false};
    auto work = [&] {
        try {
            for (int item; !failed && (item = next()) >= 0;) done(item);
        } catch (...) {
            std::lock_guard<std::mutex> hold(failure_lock);
            if (!failure) failure = std::current_exception();
            failed = true;
        }
    };
    std::vector<std::thread> helpers;
    for (int t = 1; t < threads; ++t) helpers.emplace_back(work);
    work();
    for (std::thread& h : helpers) h.join();
    if (failure) std::rethrow_exception(failure);
}

// Messages between the ranks for one figure's items.
enum Tag : int {
    tag_result = 1,   // worker -> 0: {"item", "result"}
    tag_failed = 2,   // worker -> 0: {"error"}, naming the item
    tag_request = 3,  // worker -> 0: the next item, please (dynamic)
    tag_assign = 4,   // 0 -> worker: {"item"}: -1 when none is left
    tag_done = 5,     // worker -> 0: it has sent everything
};

Cluster::Bytes cbor(const json& j) {
    return json::to_cbor(j);
}
json decoded(const Cluster::Bytes& bytes) {
    return json::from_cbor(bytes);
}

// The items of `missing` that rank `rank` of `size` runs under the fixed schedule.
std::vector<int> fixed_share(const std::vector<int>& missing, int rank, int size) {
    std::vector<int> mine;
    for (std::size_t j = static_cast<std::size_t>(rank); j < missing.size(); j += static_cast<std::size_t>(size))
        mine.push_back(missing[j]);
    return mine;
}

}  // namespace

std::string parts_name(const std::string& id) {
    return id + ".parts";
}

std::string work_hash(const description::Description& d, const scenes::WorkItems& items) {
    std::ostringstream params;
    params << toml::json_formatter{d.params};
    const std::string text = std::string(version()) + "\n" + d.scene + "\n" + std::to_string(d.seed) + "\n" +
                             params.str() + "\n" + items.depends_on();
    return render::sha256_hex(text.data(), text.size());
}

void check_merge_sources(const description::Description& d, const scenes::WorkItems& items,
                         const WorkOptions& options) {
    const int count = items.item_count();
    std::vector<bool> present(static_cast<std::size_t>(count));
    for (const std::filesystem::path& from : options.merge_from) {
        const Parts parts = Parts::given(from, d, items);
        for (int i = 0; i < count; ++i) present[i] = present[i] || parts.has(i);
    }
    std::string missing;
    int shown = 0, absent = 0;
    for (int i = 0; i < count; ++i)
        if (!present[i] && ++absent <= 3) missing += (shown++ ? ", " : "") + items.item_name(i);
    if (absent > 0)
        throw UsageError("--from: " + d.id + "'s parts lack " + std::to_string(absent) + " of " +
                         std::to_string(count) + " items (" + missing + (absent > 3 ? ", ..." : "") +
                         "); allowed: the parts of every shard (render --shard K/N for each K of N)");
}

std::vector<json> run_work(const description::Description& d, const scenes::WorkItems& items,
                           const render::Folder& folder, const WorkOptions& options, scenes::Progress& progress) {
    const int count = items.item_count();
    std::vector<std::optional<json>> results(static_cast<std::size_t>(count));
    if (options.merging()) {
        // Every --from folder's parts; the first folder holding an item gives it.
        for (const std::filesystem::path& from : options.merge_from) {
            const Parts parts = Parts::given(from, d, items);
            for (int i = 0; i < count; ++i)
                if (!results[i]) results[i] = parts.load(i);
        }
        for (int i = 0; i < count; ++i)
            if (!results[i])
                throw std::runtime_error("--from: " + d.id + "'s part of " + items.item_name(i) +
                                         " does not decode as this figure's (damaged or changed since it was "
                                         "written): render that shard again");
        progress.advance(count);
    } else {
        const Parts parts = Parts::in_output(folder, d, items);
        std::vector<int> missing;
        for (int i = 0; i < count; ++i) {
            results[i] = parts.load(i);
            if (results[i])
                progress.advance();
            else
                missing.push_back(i);
        }
        if (const std::size_t kept = static_cast<std::size_t>(count) - missing.size(); kept > 0)
            std::fprintf(stderr, "figgen: %s: resuming: %zu of %d items kept from an earlier run in %s\n", d.id.c_str(),
                         kept, count, description::printable(parts.folder().path().string()).c_str());
        std::mutex record_lock;
        auto record = [&](int item, json result) {
            parts.store(item, result);
            std::lock_guard<std::mutex> hold(record_lock);
            results[item] = std::move(result);
            progress.advance();
        };
        Cluster* cluster = options.cluster;
        if (!cluster) {
            std::atomic<std::size_t> cursor{0};
            run_on_threads(
                options.threads,
                [&] {
                    const std::size_t j = cursor++;
                    return j < missing.size() ? missing[j] : -1;
                },
                [&](int item) { record(item, run_one(d, items, item)); });
        } else {
            // Rank 0: says which items are missing, then runs its share while
            // a thread of its own serves the other ranks.
            const bool dynamic = options.schedule == Schedule::dynamic;
            Cluster::Bytes header = cbor({{"figure", d.id}, {"missing", missing}, {"dynamic", dynamic}});
            cluster->broadcast(header);
            std::atomic<std::size_t> cursor{0};
            const std::vector<int> mine = dynamic ? missing : fixed_share(missing, 0, cluster->size());
            std::atomic<bool> stop{false};     // hand out no more items
            std::atomic<bool> abandon{false};  // rank 0 failed: the server stops too, the job is aborted
            std::string rank_failure;          // the first failure another rank sent
            std::exception_ptr serve_failure;
            std::thread server([&] {
                try {
                    for (int working = cluster->size() - 1; working > 0 && !abandon;) {
                        std::optional<Cluster::Message> next = cluster->poll();
                        if (!next) {
                            std::this_thread::sleep_for(std::chrono::microseconds(200));
                            continue;
                        }
                        Cluster::Message& m = *next;
                        if (m.tag == tag_done) {
                            --working;
                        } else if (m.tag == tag_request) {
                            const std::size_t j = stop ? mine.size() : cursor++;
                            cluster->send(m.from, tag_assign, cbor({{"item", j < mine.size() ? mine[j] : -1}}));
                        } else if (m.tag == tag_result) {
                            json r = decoded(m.bytes);
                            const int item = r.at("item").get<int>();
                            if (item < 0 || item >= count) throw std::runtime_error("a result of no item");
                            record(item, std::move(r.at("result")));
                        } else if (m.tag == tag_failed) {
                            const json f = decoded(m.bytes);
                            if (rank_failure.empty())
                                rank_failure =
                                    "rank " + std::to_string(m.from) + ": " + f.at("error").get<std::string>();
                            stop = true;
                            break;  // the job ends: rank 0 reports it and aborts every rank
                        }
                    }
                } catch (...) {
                    serve_failure = std::current_exception();
                    stop = true;
                }
            });
            try {
                run_on_threads(
                    options.threads,
                    [&] {
                        const std::size_t j = stop ? mine.size() : cursor++;
                        return j < mine.size() ? mine[j] : -1;
                    },
                    [&](int item) { record(item, run_one(d, items, item)); });
            } catch (const std::exception& e) {
                stop = abandon = true;
                server.join();  // it stops at its next poll; the caller aborts the job once this is said
                throw std::runtime_error("rank 0: " + std::string(e.what()));
            }
            server.join();
            if (serve_failure) std::rethrow_exception(serve_failure);
            if (!rank_failure.empty()) throw std::runtime_error(rank_failure);
        }
    }
    std::vector<json> out;
    out.reserve(results.size());
    for (std::optional<json>& r : results) out.push_back(std::move(*r));
    return out;
}

int run_shard(const description::Description& d, const scenes::WorkItems& items, const render::Folder& folder,
              const WorkOptions& options, scenes::Progress& progress) {
    const Parts parts = Parts::in_output(folder, d, items);
    std::vector<int> missing;
    for (int i = options.shard - 1; i < items.item_count(); i += options.shards)
        if (!parts.load(i)) missing.push_back(i);
    progress.start(d.id + " shard " + std::to_string(options.shard) + "/" + std::to_string(options.shards),
                   static_cast<long long>(missing.size()));
    std::atomic<std::size_t> cursor{0};
    std::mutex progress_lock;
    run_on_threads(
        options.threads,
        [&] {
            const std::size_t j = cursor++;
            return j < missing.size() ? missing[j] : -1;
        },
        [&](int item) {
            parts.store(item, run_one(d, items, item));
            std::lock_guard<std::mutex> hold(progress_lock);
            progress.advance();
        });
    progress.finish();
    return static_cast<int>(missing.size());
}

void serve_work(const description::Description& d, const scenes::WorkItems& items, const WorkOptions& options) {
    Cluster& cluster = *options.cluster;
    Cluster::Bytes header;
    cluster.broadcast(header);
    const json h = decoded(header);
    if (h.at("figure").get<std::string>() != d.id)
        throw std::logic_error("rank " + std::to_string(cluster.rank()) + " expected " + d.id + ", rank 0 runs " +
                               h.at("figure").get<std::string>());
    const std::vector<int> missing = h.at("missing").get<std::vector<int>>();
    const bool dynamic = h.at("dynamic").get<bool>();
    const std::vector<int> mine = dynamic ? std::vector<int>() : fixed_share(missing, cluster.rank(), cluster.size());
    std::atomic<std::size_t> cursor{0};
    std::mutex ask_lock;  // one request and its answer at a time
    try {
        run_on_threads(
            options.threads,
            [&] {
                if (!dynamic) {
                    const std::size_t j = cursor++;
                    return j < mine.size() ? mine[j] : -1;
                }
                std::lock_guard<std::mutex> hold(ask_lock);
                cluster.send(0, tag_request, {});
                return decoded(cluster.wait(0, tag_assign).bytes).at("item").get<int>();
            },
            [&](int item) {
                json result;
                try {
                    result = run_one(d, items, item);
                } catch (const std::bad_alloc&) {
                    // Said by rank 0, which cannot know this node's memory: name the item here.
                    throw std::runtime_error(d.id + ", " + items.item_name(item) +
                                             ": out of memory on this rank (its node has less free than the "
                                             "item needs; see figgen's --max-memory estimate)");
                }
                cluster.send(0, tag_result, cbor({{"item", item}, {"result", result}}));
            });
    } catch (const std::exception& e) {
        // Rank 0 says it and ends the job; this rank waits for that end.
        cluster.send(0, tag_failed, cbor({{"error", e.what()}}));
        for (;;) cluster.wait(0, tag_assign);  // never sent again: only the abort ends this
    }
    cluster.send(0, tag_done, {});
}

void remove_parts(const render::Folder& folder, const std::string& id) {
    render::remove_at(folder, parts_name(id));
}

}  // namespace app
