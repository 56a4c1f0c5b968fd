#include "app/work/schedule.hpp"

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

#include "app/work/bounded_json.hpp"
#include "app/work/parts.hpp"
#include "base/digest.hpp"
#include "base/version.hpp"
#include "description/plain_name.hpp"

namespace app {

using description::UsageError;
using nlohmann::json;

namespace {

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


}  // namespace app
