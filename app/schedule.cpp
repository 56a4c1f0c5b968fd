#include "app/schedule.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/bounded_json.hpp"
#include "app/figure_lock.hpp"
#include "app/version.hpp"
#include "description/plain_name.hpp"
#include "base/digest.hpp"

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
            {"figgen", version()},
            {"figure", d.id},
            {"description_sha256", work_hash(d, items)},
            {"items", names}};
}

std::string sha256_of(const std::string& text) {
    return base::sha256_hex(text.data(), text.size());
}

// A part as Parts::load found it.
struct Part {
    enum class State { absent, sound, damaged };
    State state = State::absent;
    json result;          // sound: the item's result, checked
    std::string problem;  // damaged: what is wrong, after "<folder>/item-000017.cbor (tile 17) "
};

// The manifest's value of `key` for a message: its JSON, shortened.
std::string shown_value(const json& manifest, const char* key) {
    const auto it = manifest.find(key);
    return it == manifest.end() ? "none" : description::printable(it->dump(), 80);
}

// A figure's parts folder: its manifest and one file per finished item.
// A part is the CBOR map {item, name, manifest_sha256, result_sha256,
// result}: its result as CBOR bytes of their own and their SHA-256, so that
// a part changed since it was written is told from one that was not; the
// manifest's hash ties it to this figure, settings and figgen.
class Parts {
public:
    // The parts folder of `d` in `out`, made when missing. Parts of another
    // manifest there are stale: they are removed, and the run says so.
    static Parts in_output(const base::Folder& out, const description::Description& d, const scenes::WorkItems& items) {
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

    // The parts a merge was given with --from: the folder itself or the
    // output folder that holds it (a real folder there, not a symlink);
    // refused (UsageError) unless its manifest is this run's.
    static Parts given(const std::filesystem::path& path, const description::Description& d,
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

    // Item `item`'s part: absent, sound (its result checked by the scene)
    // or damaged (and why).
    Part load(int item) const {
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

    // Whether a regular file stands at item `item`'s part (not yet whether it is sound).
    bool has(int item) const {
        struct stat st {};
        return ::fstatat(folder_.fd(), part_name(item).c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode);
    }

    void store(int item, const json& result) const {
        // Put in place at once, not with the figure's files: a run killed
        // before the figure is written keeps it.
        base::write_file_atomically(folder_, part_name(item), part_bytes(item, result, items_, manifest_sha256_),
                                    base::AtomicFile::Commit::now);
    }

    // "<folder>/item-000017.cbor (tile 17)": what messages call a part.
    std::string named(int item) const {
        return description::printable((folder_ / part_name(item)).string()) + " (" + items_.item_name(item) + ")";
    }

    const base::Folder& folder() const { return folder_; }

private:
    Parts(base::Folder folder, const scenes::WorkItems& items, json manifest)
        : folder_(std::move(folder)),
          items_(items),
          manifest_(std::move(manifest)),
          manifest_sha256_(sha256_of(manifest_.dump())),
          max_part_bytes_(items.item_bytes() + 65536) {}

    // The manifest, none when there is none; `problem` says why one that is
    // there cannot be read.
    std::optional<json> read_manifest(std::string& problem) const {
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

    base::Folder folder_;
    const scenes::WorkItems& items_;
    json manifest_;
    std::string manifest_sha256_;
    double max_part_bytes_;
};

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
    return app::cbor_bounded(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// The items of `missing` that rank `rank` of `size` runs under the fixed schedule.
std::vector<int> fixed_share(const std::vector<int>& missing, int rank, int size) {
    std::vector<int> mine;
    for (std::size_t j = static_cast<std::size_t>(rank); j < missing.size(); j += static_cast<std::size_t>(size))
        mine.push_back(missing[j]);
    return mine;
}

}  // namespace

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
    const std::string text = std::string(version()) + "\n" + d.scene + "\n" + std::to_string(d.seed) + "\n" +
                             params.str() + "\n" + items.depends_on();
    return base::sha256_hex(text.data(), text.size());
}

void check_merge_sources(const description::Description& d, const scenes::WorkItems& items,
                         const WorkOptions& options) {
    const int count = items.item_count();
    std::vector<bool> present(static_cast<std::size_t>(count));
    for (const std::filesystem::path& from : options.merge_from) {
        const Parts parts = Parts::given(from, d, items);
        // Each part is read and checked here, before anything is created,
        // and read again when the figure is drawn (holding every figure's
        // results from now until then would cost more than the estimates count).
        for (int i = 0; i < count; ++i) {
            if (present[i] || !parts.has(i)) continue;
            const Part part = parts.load(i);
            if (part.state == Part::State::damaged) throw damaged_part(parts, i, part);
            present[i] = true;
        }
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

namespace {

using Results = std::vector<std::optional<json>>;
using Record = std::function<void(int item, json result)>;

// figgen merge: every item from the parts of the --from folders; the first
// folder holding an item gives it.
void gather_from_parts(const description::Description& d, const scenes::WorkItems& items, const WorkOptions& options,
                       Results& results, scenes::Progress& progress) {
    const int count = items.item_count();
    for (const std::filesystem::path& from : options.merge_from) {
        const Parts parts = Parts::given(from, d, items);
        for (int i = 0; i < count; ++i) {
            if (results[i]) continue;
            Part part = parts.load(i);
            if (part.state == Part::State::damaged) throw damaged_part(parts, i, part);
            if (part.state == Part::State::sound) results[i] = std::move(part.result);
        }
    }
    for (int i = 0; i < count; ++i)
        if (!results[i])
            throw UsageError("--from: " + d.id + "'s parts lack " + items.item_name(i) +
                             "; allowed: the parts of every shard (render --shard K/N for each K of N)");
    progress.advance(count);
}

// The missing items on this process's threads, each taking the next.
void run_here(const description::Description& d, const scenes::WorkItems& items, const std::vector<int>& missing,
              int threads, const Record& record) {
    std::atomic<std::size_t> cursor{0};
    run_on_threads(
        threads,
        [&] {
            const std::size_t j = cursor++;
            return j < missing.size() ? missing[j] : -1;
        },
        [&](int item) { record(item, run_one(d, items, item)); });
}

// Rank 0 of an MPI job: says which items are missing, then runs its share
// while a thread of its own serves the other ranks (their requests, results
// and failures). The first failure, here or on a rank, ends the job.
void run_as_rank_zero(const description::Description& d, const scenes::WorkItems& items,
                      const std::vector<int>& missing, const WorkOptions& options, const Record& record) {
    Cluster* cluster = options.cluster;
    const int count = items.item_count();
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
                        rank_failure = "rank " + std::to_string(m.from) + ": " + f.at("error").get<std::string>();
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

}  // namespace

std::vector<json> run_work(const description::Description& d, const scenes::WorkItems& items,
                           const base::Folder& folder, const WorkOptions& options, scenes::Progress& progress) {
    const int count = items.item_count();
    Results results(static_cast<std::size_t>(count));
    if (options.merging()) {
        gather_from_parts(d, items, options, results, progress);
    } else {
        // The items kept from an earlier run are used; the rest are run,
        // each kept as a part as it finishes.
        const Parts parts = Parts::in_output(folder, d, items);
        std::vector<int> missing;
        for (int i = 0; i < count; ++i) {
            results[i] = kept_result(parts, d.id, i);
            if (results[i])
                progress.advance();
            else
                missing.push_back(i);
        }
        if (const std::size_t kept = static_cast<std::size_t>(count) - missing.size(); kept > 0)
            std::fprintf(stderr, "figgen: %s: resuming: %zu of %d items kept from an earlier run in %s\n", d.id.c_str(),
                         kept, count, description::printable(parts.folder().path().string()).c_str());
        std::mutex record_lock;
        const Record record = [&](int item, json result) {
            parts.store(item, result);
            std::lock_guard<std::mutex> hold(record_lock);
            results[item] = std::move(result);
            progress.advance();
        };
        if (options.cluster) run_as_rank_zero(d, items, missing, options, record);
        else run_here(d, items, missing, options.threads, record);
    }
    std::vector<json> out;
    out.reserve(results.size());
    for (std::optional<json>& r : results) out.push_back(std::move(*r));
    return out;
}

int run_shard(const description::Description& d, const scenes::WorkItems& items, const base::Folder& folder,
              const WorkOptions& options, scenes::Progress& progress) {
    const Parts parts = Parts::in_output(folder, d, items);
    std::vector<int> missing;
    for (int i = options.shard - 1; i < items.item_count(); i += options.shards)
        if (!kept_result(parts, d.id, i)) missing.push_back(i);
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

void remove_parts(const base::Folder& folder, const std::string& id) {
    base::remove_at(folder, parts_name(id));
}

}  // namespace app
