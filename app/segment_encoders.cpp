#include "app/segment_encoders.hpp"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace app {

// One segment: its frames waiting, and the worker that encodes them.
struct SegmentEncoders::Segment {
    std::mutex lock;
    std::condition_variable changed;
    std::deque<render::Image> waiting;
    int frames = 0;        // frames given to it so far
    bool closed = false;   // no more frames will come
    bool stopped = false;  // give up: the film is abandoned
    bool done = false;     // packets (or failure) are set
    std::vector<render::VideoPacket> packets;
    std::exception_ptr failure;
    std::thread worker;  // last: started once everything above exists

    // `taken` is called after each frame is taken from `waiting`.
    template <class Taken>
    void encode(const std::string& shown, int width, int height, const render::VideoOptions& options, Taken taken) {
        try {
            render::VideoSegment encoder(shown, width, height, options);
            for (;;) {
                render::Image frame;
                {
                    std::unique_lock<std::mutex> hold(lock);
                    changed.wait(hold, [&] { return stopped || closed || !waiting.empty(); });
                    if (stopped) break;
                    if (waiting.empty()) {  // closed, every frame encoded
                        hold.unlock();
                        std::vector<render::VideoPacket> encoded = encoder.finish();
                        hold.lock();
                        packets = std::move(encoded);
                        break;
                    }
                    frame = std::move(waiting.front());
                    waiting.pop_front();
                }
                taken();
                encoder.add(frame);
            }
        } catch (...) {
            std::lock_guard<std::mutex> hold(lock);
            failure = std::current_exception();
        }
        std::lock_guard<std::mutex> hold(lock);
        done = true;
        changed.notify_all();
    }
};

SegmentEncoders::SegmentEncoders(render::VideoWriter& writer, std::string shown, int width, int height,
                                 const render::VideoOptions& options, int workers)
    : writer_(writer), shown_(std::move(shown)), width_(width), height_(height), options_(options), workers_(workers) {
    if (options.segment_frames < 1) throw std::invalid_argument("SegmentEncoders: segment_frames < 1");
    if (workers < 1) throw std::invalid_argument("SegmentEncoders: workers < 1");
}

SegmentEncoders::~SegmentEncoders() { stop_all(); }

void SegmentEncoders::stop_all() {
    for (const std::unique_ptr<Segment>& s : open_) {
        {
            std::lock_guard<std::mutex> hold(s->lock);
            s->stopped = true;
        }
        s->changed.notify_all();
    }
    for (const std::unique_ptr<Segment>& s : open_)
        if (s->worker.joinable()) s->worker.join();
    open_.clear();
}

void SegmentEncoders::add(render::Image frame) {
    Segment* last = open_.empty() ? nullptr : open_.back().get();
    if (!last || last->frames == options_.segment_frames) {
        if (last) {
            std::lock_guard<std::mutex> hold(last->lock);
            last->closed = true;
            last->changed.notify_all();
        }
        if (static_cast<int>(open_.size()) == workers_) write_oldest();
        auto segment = std::make_unique<Segment>();
        Segment* s = segment.get();
        s->worker = std::thread([this, s] {
            s->encode(shown_, width_, height_, options_, [this] {
                {
                    std::lock_guard<std::mutex> hold(lock_);
                    --waiting_;
                }
                taken_.notify_all();
            });
            // Ended (a failure among the reasons): add() looks again.
            { std::lock_guard<std::mutex> hold(lock_); }
            taken_.notify_all();
        });
        open_.push_back(std::move(segment));
        last = s;
    }
    // A failed segment stops the film now rather than at finish().
    {
        Segment& oldest = *open_.front();
        std::lock_guard<std::mutex> hold(oldest.lock);
        if (oldest.failure) std::rethrow_exception(oldest.failure);
    }
    {
        // Room for one more waiting frame, unless an encoder failed (it
        // takes no more; its failure is thrown below or at the next add).
        const int most = waiting_most(workers_, options_.segment_frames);
        std::unique_lock<std::mutex> hold(lock_);
        taken_.wait(hold, [&] {
            if (waiting_ < most) return true;
            for (const std::unique_ptr<Segment>& s : open_) {
                std::lock_guard<std::mutex> segment(s->lock);
                if (s->failure) return true;
            }
            return false;
        });
        ++waiting_;
    }
    std::lock_guard<std::mutex> hold(last->lock);
    if (last->failure) std::rethrow_exception(last->failure);
    last->waiting.push_back(std::move(frame));
    ++last->frames;
    last->changed.notify_all();
}

void SegmentEncoders::write_oldest() {
    Segment& s = *open_.front();
    {
        std::unique_lock<std::mutex> hold(s.lock);
        s.changed.wait(hold, [&] { return s.done; });
        if (s.failure) std::rethrow_exception(s.failure);
    }
    s.worker.join();
    writer_.add_segment(s.packets, s.frames);
    open_.pop_front();
}

void SegmentEncoders::finish() {
    if (!open_.empty()) {
        Segment& last = *open_.back();
        std::lock_guard<std::mutex> hold(last.lock);
        last.closed = true;
        last.changed.notify_all();
    }
    while (!open_.empty()) write_oldest();
}

}  // namespace app
