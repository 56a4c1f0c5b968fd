#include "figures/outputs.hpp"

#include <cmath>
#include <cstdio>

#include "figures/version.hpp"
#include "render/atomic_file.hpp"
#include "render/gl_context.hpp"
#include "render/png_io.hpp"

namespace figures {

int scaled_even(int pixels, double scale) {
    const int scaled = static_cast<int>(std::lround(pixels * scale));
    return std::max(2, scaled + (scaled % 2));
}

int figure_width(const Description& d, const OutputOptions& options) {
    return scaled_even(d.width, options.scale);
}
int figure_height(const Description& d, const OutputOptions& options) {
    return scaled_even(d.height, options.scale);
}

FrameSink::FrameSink(const Description& d, const OutputOptions& options, int width, int height)
    : description_(d), options_(options), width_(width), height_(height) {
    if (options.video)
        video_ = std::make_unique<render::VideoWriter>(options.dir / (d.id + ".mp4"), width, height, [&] {
            render::VideoOptions v = options.video_options;
            v.fps = d.animation->fps;
            return v;
        }());
    if (options.frames) {
        frames_dir_ = options.dir / (d.id + "-frames");
        std::error_code ec;
        std::filesystem::create_directories(frames_dir_, ec);
        if (ec) throw std::runtime_error("cannot create " + frames_dir_.string() + ": " + ec.message());
    }
}

FrameSink::~FrameSink() = default;

void FrameSink::add(const render::Image& frame, int step) {
    if (video_) video_->add(frame);
    if (!frames_dir_.empty()) {
        char name[32];
        std::snprintf(name, sizeof name, "%05d.png", static_cast<int>(steps_.size()));
        render::write_png(frames_dir_ / name, frame,
                          {{"Title", description_.id + " " + format_step("step {step}", step)}});
    }
    steps_.push_back(step);
}

nlohmann::json FrameSink::finish() {
    nlohmann::json meta = {
        {"frames", steps_.size()},
        {"first", description_.animation->first},
        {"last", description_.animation->last},
        {"stride", description_.animation->stride},
        {"steps", steps_},
        {"fps", description_.animation->fps},
        {"size", {width_, height_}},
    };
    if (video_) {
        video_->finish();
        meta["file"] = description_.id + ".mp4";
        meta["codec"] = video_->codec_name();
        meta["pixel_format"] = "yuv420p";
        meta["encoder_threads"] = options_.video_options.threads;
    }
    if (!frames_dir_.empty()) meta["png_sequence"] = description_.id + "-frames";
    return meta;
}

void write_figure(const Description& d, const OutputOptions& options, const render::Image& image,
                  nlohmann::json metadata) {
    const auto& gl = render::GlContext::get();
    nlohmann::json meta = {
        {"id", d.id},
        {"title", d.title},
        {"source", d.source},
        {"model", d.model},
        {"caption", d.caption},
        {"seed", d.seed},
        {"description", d.file.filename().string()},
        {"figgen_version", version()},
        {"renderer", {{"gl_renderer", gl.renderer()}, {"gl_version", gl.version()}}},
        {"scale", options.scale},
    };
    meta.update(metadata);
    meta["image"] = {{"file", d.id + ".png"}, {"size", {image.width, image.height}}};

    render::write_png(options.dir / (d.id + ".png"), image,
                      {{"Title", d.title},
                       {"Source", d.source},
                       {"Software", std::string("figgen ") + version()},
                       {"figgen:id", d.id},
                       {"figgen:seed", std::to_string(d.seed)},
                       {"figgen:params", meta.value("params", nlohmann::json::object()).dump()}});
    render::write_file_atomically(options.dir / (d.id + ".json"), meta.dump(2) + "\n");
}

}  // namespace figures
