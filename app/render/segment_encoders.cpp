#include "app/render/segment_encoders.hpp"

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
    int number = 0;        // in film order, from 0
    int first = 0;         // the film's index of its first frame
    std::vector<media::VideoPacket> packets;
    std::exception_ptr failure;
    std::thread worker;  // last: started once everything above exists

    // `taken` is called after each frame is taken from `waiting`.
    // `preview(number, frames)` adds its preview frames in turn.
    template <class Taken, class Preview>
    void encode(const std::string& shown, int width, int height, const media::VideoOptions& options,
                const std::vector<int>& preview_wanted, const media::PreviewOptions& preview_options, Taken taken,
                Preview preview) {
        try {
            media::VideoSegment encoder(shown, width, height, options);
            for (;;) {
                render::Image frame;
                {
                    std::unique_lock<std::mutex> hold(lock);
                    changed.wait(hold, [&] { return stopped || closed || !waiting.empty(); });
                    if (stopped) break;
                    if (waiting.empty()) {  // closed, every frame encoded
                        const int count = frames;
                        hold.unlock();
                        std::vector<media::VideoPacket> encoded = encoder.finish();
                        std::vector<int> local;
                        for (int wanted : preview_wanted)
                            if (wanted >= first && wanted < first + count) local.push_back(wanted - first);
                        std::vector<render::Image> shown_frames;
                        if (!local.empty()) shown_frames = encoder.preview_frames(encoded, local, preview_options);
                        preview(number, std::move(shown_frames));
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

SegmentEncoders::SegmentEncoders(media::VideoWriter& writer, std::string shown, int width, int height,
                                 const media::VideoOptions& options, int workers, int film_frames,
                                 const media::PreviewOptions& preview)
    : writer_(writer),
      shown_(std::move(shown)),
      width_(width),
      height_(height),
      options_(options),
      workers_(workers),
      film_frames_(film_frames),
      preview_options_(preview) {
    if (options.segment_frames < 1) throw std::invalid_argument("SegmentEncoders: segment_frames < 1");
    if (workers < 1) throw std::invalid_argument("SegmentEncoders: workers < 1");
    if (film_frames < 0) throw std::invalid_argument("SegmentEncoders: film_frames < 0");
    if (film_frames > 0) {
        preview_wanted_ = media::preview_frame_indices(film_frames, preview);
        preview_ = std::make_unique<media::PreviewAnimation>(shown_, film_frames, options.fps, preview);
    }
}

void SegmentEncoders::add_preview(int number, std::vector<render::Image> frames) {
    std::unique_lock<std::mutex> hold(preview_lock_);
    preview_turn_.wait(hold, [&] { return preview_abandoned_ || preview_next_ == number; });
    if (preview_abandoned_) return;
    try {
        for (render::Image& frame : frames) preview_->add(std::move(frame));
    } catch (...) {
        preview_abandoned_ = true;  // the writer decodes the film for its preview
    }
    ++preview_next_;
    preview_turn_.notify_all();
}

void SegmentEncoders::abandon_preview() {
    {
        std::lock_guard<std::mutex> hold(preview_lock_);
        preview_abandoned_ = true;
    }
    preview_turn_.notify_all();
}

SegmentEncoders::~SegmentEncoders() {
    stop_all();
}

void SegmentEncoders::stop_all() {
    abandon_preview();
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
        s->number = segments_++;
        s->first = frames_added_;
        s->worker = std::thread([this, s] {
            s->encode(
                shown_, width_, height_, options_, preview_wanted_, preview_options_,
                [this] {
                    {
                        std::lock_guard<std::mutex> hold(lock_);
                        --waiting_;
                    }
                    taken_.notify_all();
                },
                [this](int number, std::vector<render::Image> frames) { add_preview(number, std::move(frames)); });
            // A segment that failed adds no preview frames: the others need not wait for it.
            {
                std::lock_guard<std::mutex> hold(s->lock);
                if (s->failure) abandon_preview();
            }
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
    ++frames_added_;
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
    frames_written_ += s.frames;
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
    // A film that ended where it was planned to: its preview is decoded
    // already (else the writer decodes the film).
    if (preview_ && frames_written_ == film_frames_ && preview_->complete()) writer_.set_preview(std::move(preview_));
}

}  // namespace app
