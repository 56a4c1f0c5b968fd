#pragma once
// A film's segments encoded side by side. Frames arrive in film order from
// one thread; every segment_frames of them make a segment, encoded on a
// worker thread of its own by an encoder of its own (render::VideoSegment:
// one x264 thread, a closed group of pictures from a key frame), and the
// segments are joined in film order by stream copy (VideoWriter::
// add_segment). Each segment's bytes depend only on its frames, so the MP4
// is the same bytes whatever the number of workers, cores or ranks and
// however loaded the machine is: the film of a lone process, of one worker,
// and of an MPI job whose ranks each encode some segments.
//
// At most `workers` segments are open at once, and at most waiting_most()
// frames wait for their encoders, (workers - 1) x segment_frames and a few:
// enough for the segments before the newest to wait whole while the newest
// is fed, never the whole film (app/outputs.cpp's estimate counts them).

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include "render/image.hpp"
#include "render/video.hpp"

namespace app {

class SegmentEncoders {
public:
    // `writer` receives every segment; width x height frames encoded with
    // `options` (its segment_frames >= 1 is the segment length); workers >= 1.
    SegmentEncoders(render::VideoWriter& writer, std::string shown, int width, int height,
                    const render::VideoOptions& options, int workers);
    // Without finish(): stops every worker after the frame it is on, and
    // nothing more reaches the writer.
    ~SegmentEncoders();
    SegmentEncoders(const SegmentEncoders&) = delete;
    SegmentEncoders& operator=(const SegmentEncoders&) = delete;

    // The film's next frame. Waits while `workers` segments are open and the
    // oldest is still encoding; rethrows what a worker threw.
    void add(render::Image frame);
    // Every segment encoded and handed to the writer, in order.
    void finish();

    int workers() const { return workers_; }
    // The most frames that wait for encoders at once.
    static int waiting_most(int workers, int segment_frames) { return (workers - 1) * segment_frames + 4; }

private:
    struct Segment;
    void write_oldest();  // waits for the oldest open segment and hands it to the writer
    void stop_all();

    render::VideoWriter& writer_;
    std::string shown_;
    int width_, height_;
    render::VideoOptions options_;
    int workers_;
    std::deque<std::unique_ptr<Segment>> open_;  // in film order; the last takes the frames
    // Frames waiting in every open segment, and what add() waits on when
    // there are waiting_most() of them.
    std::mutex lock_;
    std::condition_variable taken_;
    int waiting_ = 0;
};

}  // namespace app
