#include "app/render/frame_canvas.hpp"

#include <utility>

namespace app {

FrameCanvas::FrameCanvas(int width, int height, Deliver deliver)
    : width_(width), height_(height), deliver_(std::move(deliver)) {}

FrameCanvas::~FrameCanvas() = default;

void FrameCanvas::draw(const scenes::FrameDrawing& frame, int step) {
    if (!canvas_) canvas_ = std::make_unique<render::Canvas>(width_, height_, frame.samples, frame.depth);
    frame.draw(*canvas_);
    if (!reader_) reader_ = std::make_unique<render::FrameReader>();
    reading_.push_back(step);
    if (std::optional<render::Image> image = reader_->read(*canvas_)) {
        const int drawn = reading_.front();
        reading_.pop_front();
        deliver_(std::move(*image), drawn);
    }
}

void FrameCanvas::flush() {
    if (!reader_) return;
    while (std::optional<render::Image> image = reader_->next()) {
        const int drawn = reading_.front();
        reading_.pop_front();
        deliver_(std::move(*image), drawn);
    }
}

render::Image drawn_image(const scenes::FrameDrawing& frame, int width, int height) {
    render::Canvas canvas(width, height, frame.samples, frame.depth);
    frame.draw(canvas);
    return canvas.read();
}

}  // namespace app
