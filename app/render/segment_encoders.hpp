#pragma once
// A film's segments encoded side by side. Frames arrive in film order from
// one thread; every segment_frames of them make a segment, encoded on a
// worker thread of its own by an encoder of its own (media::VideoSegment:
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
// is fed, never the whole film (app/render/output_files.cpp's estimate counts them).

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "media/video.hpp"
#include "render/image.hpp"

namespace app {

class SegmentEncoders {
public:
    // `writer` receives every segment; width x height frames encoded with
    // `options` (its segment_frames >= 1 is the segment length); workers >= 1.
    // For a film planned to have `film_frames` frames (0: unknown), each
    // worker also decodes back the preview's frames of its segment (render::
    // preview_frame_indices with `preview`) and, in film order, adds them to
    // the preview's animation, beside the drawing rather than after the
    // film; finish() gives the animation to the writer.
    SegmentEncoders(media::VideoWriter& writer, std::string shown, int width, int height,
                    const media::VideoOptions& options, int workers, int film_frames = 0,
                    const media::PreviewOptions& preview = {});
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
    // Segment `number`'s preview frames, added when the segments before it have added theirs.
    void add_preview(int number, std::vector<render::Image> frames);
    void abandon_preview();  // no more preview frames: no worker waits for its turn
    void stop_all();

    media::VideoWriter& writer_;
    std::string shown_;
    int width_, height_;
    media::VideoOptions options_;
    int workers_;
    int film_frames_;  // planned, 0: unknown
    media::PreviewOptions preview_options_;
    std::vector<int> preview_wanted_;  // the film's frames the preview shows
    std::unique_ptr<media::PreviewAnimation> preview_;
    // Whose turn it is to add to preview_: the segments' numbers, in film
    // order; a failed or stopped film lets every worker go.
    std::mutex preview_lock_;
    std::condition_variable preview_turn_;
    int preview_next_ = 0;
    bool preview_abandoned_ = false;
    int segments_ = 0;        // segments begun
    int frames_written_ = 0;  // frames in the segments written so far
    int frames_added_ = 0;
    std::deque<std::unique_ptr<Segment>> open_;  // in film order; the last takes the frames
    // Frames waiting in every open segment, and what add() waits on when
    // there are waiting_most() of them.
    std::mutex lock_;
    std::condition_variable taken_;
    int waiting_ = 0;
};

}  // namespace app
