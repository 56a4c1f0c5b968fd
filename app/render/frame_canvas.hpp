#pragma once
// Where a film's frames are drawn: one GL canvas for the whole film (made
// from the first frame's samples and depth buffer), read back through pixel
// buffers a few frames behind the drawing (render::FrameReader), each image
// handed on with its step in the order drawn. Scenes hand frames as
// drawings (scenes::FrameDrawing); this is the surface that draws them.

#include <deque>
#include <functional>
#include <memory>

#include "render/gl/canvas.hpp"
#include "render/image.hpp"
#include "scenes/output.hpp"

namespace app {

class FrameCanvas {
public:
    using Deliver = std::function<void(render::Image frame, int step)>;

    // Frames of width x height pixels, each passed to `deliver` once read back.
    FrameCanvas(int width, int height, Deliver deliver);
    ~FrameCanvas();
    FrameCanvas(const FrameCanvas&) = delete;
    FrameCanvas& operator=(const FrameCanvas&) = delete;

    // Draws `frame` and starts reading it back; an earlier frame may be
    // delivered meanwhile.
    void draw(const scenes::FrameDrawing& frame, int step);
    // Delivers every frame drawn so far.
    void flush();

private:
    int width_, height_;
    Deliver deliver_;
    std::unique_ptr<render::Canvas> canvas_;
    std::unique_ptr<render::FrameReader> reader_;
    std::deque<int> reading_;  // the steps of the frames in flight
};

// `frame` drawn once on a fresh canvas of width x height and read back
// (benchmarks, tests).
render::Image drawn_image(const scenes::FrameDrawing& frame, int width, int height);

}  // namespace app
