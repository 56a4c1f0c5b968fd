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
// At most `workers` segments are open at once; the frames of an open
// segment wait for its encoder, so at most workers x segment_frames frames
// are held (app/outputs.cpp's estimate counts them), never the whole film.

#include <deque>
#include <memory>
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
};

}  // namespace app
