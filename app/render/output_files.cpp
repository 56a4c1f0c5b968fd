#include "app/render/output_files.hpp"

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <utility>

#include "app/render/film_segments.hpp"
#include "app/render/formats.hpp"
#include "base/atomic_file.hpp"
#include "base/version.hpp"
#include "media/png_io.hpp"
#include "ready/writers/vti_file.hpp"
#include "ready/writers/vtu_file.hpp"
#include "render/gl/canvas.hpp"
#include "render/gl/gl_context.hpp"
#include "render/vector/vector.hpp"
#include "render/vector/vector_page.hpp"
#include "scenes/helpers/figure_caption.hpp"

namespace app {

using scenes::scaled;

namespace {

// The film's preview: render's defaults.
const media::PreviewOptions preview_options{};

}  // namespace

FrameSink::FrameSink(const Description& d, const OutputOptions& options, const base::Folder& folder, int width,
                     int height, const std::vector<nlohmann::json>* segments, int encoders)
    : description_(d),
      options_(options),
      folder_(folder),
      width_(width),
      height_(height),
      segments_(segments),
      canvas_(width, height, [this](render::Image frame, int step) { pipe_->push(std::move(frame), step); }) {
    if (options.encodes()) {
        const media::VideoOptions video = film_video_options(d, options);
        video_ = std::make_unique<media::VideoWriter>(folder, d.id + ".mp4", width, height, video);
        // Segments side by side; a film of one segment, or one encoder, as before.
        if (!segments && encoders > 1 && video.segment_frames > 0)
            encoders_ = std::make_unique<SegmentEncoders>(*video_, (folder / (d.id + ".mp4")).string(), width, height,
                                                          video, encoders, d.animation->frame_count(), preview_options);
    }
    if (options.frames) {
        frames_ = std::make_unique<base::AtomicDir>(folder, d.id + "-frames");
    }
    pipe_ = std::make_unique<FramePipe>([this](render::Image& frame, int step) { write(frame, step); }, frames_queued);
}

FrameSink::~FrameSink() = default;

void FrameSink::add(const scenes::FrameDrawing& frame, int step) {
    canvas_.draw(frame, step);
}

void FrameSink::flush() {
    canvas_.flush();
}

void FrameSink::write(render::Image& frame, int step) {
    if (frames_) {
        char name[32];
        std::snprintf(name, sizeof name, "%05d.png", static_cast<int>(steps_.size()));
        media::write_png(frames_->folder(), name, frame,
                          {{"Title", description_.id + " " + description::format_step("step {step}", step)}},
                          base::AtomicFile::Commit::now,  // inside the temporary folder
                          media::PngCompression::fast);
    }
    if (encoders_)
        encoders_->add(std::move(frame));
    else if (video_)
        video_->add(frame);
    steps_.push_back(step);
}

nlohmann::json FrameSink::finish() {
    canvas_.flush();
    pipe_->finish();                     // every frame encoded and written, or what failed is thrown here
    if (encoders_) encoders_->finish();  // every segment in the MP4
    if (segments_)
        for (const nlohmann::json& segment : *segments_) {
            const FilmSegment s = film_segment(segment);
            if (video_) video_->add_segment(s.packets, static_cast<int>(s.steps.size()));
            for (int step : s.steps) steps_.push_back(step);
        }
    nlohmann::json meta = {
        {"frames", steps_.size()},
        {"first", description_.animation->first},
        {"last", description_.animation->last},
        {"stride", description_.animation->stride},
        {"steps", steps_},
        {"fps", description_.animation->fps},
        {"size", {width_, height_}},
    };
    if (description_.animation->turn_frames > 0) meta["turn_frames"] = description_.animation->turn_frames;
    // The poster: the frame of the step the description names (the last
    // frame before it where the run stopped early), else the last frame.
    if (!steps_.empty()) {
        std::size_t frame = steps_.size() - 1;
        if (const std::optional<int>& poster = description_.animation->poster)
            while (frame > 0 && steps_[frame].get<int>() > *poster) --frame;
        meta["poster"] = {{"frame", frame}, {"step", steps_[frame]}};
    }
    // The film rounds its size up to even (H.264 in yuv420p needs it); the figure keeps its own.
    const int asked_width = scaled(description_.animation->width, options_.scale),
              asked_height = scaled(description_.animation->height, options_.scale);
    if (asked_width != width_ || asked_height != height_)
        meta["size_rounded"] = {{"from", {asked_width, asked_height}}, {"why", "H.264 in yuv420p needs even sizes"}};
    if (video_) {
        const media::WebmOptions webm;
        const auto copies = video_->finish(folder_, description_.id + ".webp", preview_options,
                                           options_.webm ? description_.id + ".webm" : "", webm, options_.video);
        const media::PreviewInfo& preview = copies.preview;
        if (options_.video) meta["file"] = description_.id + ".mp4";
        if (options_.webm)
            meta["webm"] = {{"file", description_.id + ".webm"},
                            {"codec", "libvpx-vp9"},
                            {"crf", webm.crf},
                            {"speed", webm.speed},
                            {"bytes", copies.webm_bytes}};
        meta["preview"] = {{"file", description_.id + ".webp"},
                           {"frames", preview.frames},
                           {"size", {preview.width, preview.height}},
                           {"duration_ms", preview.duration_ms},
                           {"quality", preview.quality}};
        meta["codec"] = video_->codec_name();
        if (video_->codec_name() == "libx264") {             // the mpeg4 fallback has neither
            meta["preset"] = options_.video_options.preset;  // with the settings below they shape the bytes
            meta["tune"] = options_.video_options.tune;      // "" = none
        }
        meta["pixel_format"] = "yuv420p";
        meta["encoder_threads"] = options_.video_options.threads;
        meta["segment_frames"] = description_.animation->segment_frames;
    }
    if (frames_) {
        frames_->commit();
        meta["png_sequence"] = description_.id + "-frames";
    }
    return meta;
}

std::unique_ptr<scenes::Film> FigureFiles::film(int width, int height) {
    if (!description_.animation || !options_.animates()) return nullptr;
    // As many encoders as the estimate allowed, but no more than --threads.
    return std::make_unique<FrameSink>(description_, options_, folder_, width, height, film_segments_,
                                       std::max(1, std::min(memory_.film_encoders, options_.work.threads)));
}

void FigureFiles::figure(const scenes::FigureDrawing& scene, nlohmann::json metadata) {
    const scenes::FigureCaption caption =
        scenes::figure_caption(description_, scaled(description_.width, options_.scale),
                               scaled(description_.height, options_.scale), options_.scale);
    const scenes::FigureDrawing drawing = scenes::with_caption(scene, caption);
    if (!caption.lines.empty())
        metadata["figure_caption"] = {{"shows", description_.figure_caption},
                                      {"lines", caption.lines},
                                      {"language", caption.language},
                                      {"band", caption.band}};
    render::Image image;
    {
        render::Canvas canvas(drawing.width, drawing.height, render::canvas_samples, drawing.depth);
        canvas.set_transparent(options_.transparent);
        drawing.draw(canvas);
        image = canvas.read();
    }  // the canvas's GL storage goes before the PNG is encoded
    nlohmann::json vector = nlohmann::json::object();
    for (const OutputFormat& f : output_formats()) {
        if (!f.vector || !f.wanted(description_, options_)) continue;
        render::VectorPage page(drawing.width, drawing.height, options_.transparent);
        drawing.draw(page);
        page.page().title = description_.title;
        page.page().creator = std::string("figgen ") + base::version();
        const std::string file_name = description_.id + f.suffix;
        base::AtomicFile file(folder_, file_name);
        render::vector::write(file.fd(), file.final_path(), *f.vector, page.page(),
                              static_cast<std::uint64_t>(render::vector::file_bytes(drawing.width, drawing.height)));
        struct stat info {};
        const double bytes = ::fstat(file.fd(), &info) == 0 ? static_cast<double>(info.st_size) : 0.0;
        file.commit();  // with the figure's other files (render_figure's CommitGroup)
        vector[f.name] = {{"file", file_name}, {"bytes", bytes}};
    }
    if (!vector.empty()) metadata["vector"] = std::move(vector);
    for (const bool mesh : {false, true}) {
        if (!(mesh ? options_.vtu : options_.vti)) continue;
        const char* format = mesh ? "vtu" : "vti";
        if (!drawing.ready_state) throw std::logic_error(description_.id + ": its scene writes no Ready file");
        const ready::ReadyState state = drawing.ready_state();
        if (!state.mesh != !mesh) throw std::logic_error(description_.id + ": its scene writes no ." + format + " file");
        const std::string file_name = description_.id + "." + format;
        const std::string bytes = mesh ? ready::ready_vtu(state) : ready::ready_vti(state);
        base::write_file_atomically(folder_, file_name, bytes);  // with the figure's other files
        metadata[format] = {{"file", file_name}, {"bytes", bytes.size()}};
    }
    write_figure(description_, options_, folder_, memory_, image, std::move(metadata));
}

std::vector<std::string> output_names(const std::string& id) {
    std::vector<std::string> names;
    for (const OutputFormat& f : output_formats()) names.push_back(id + f.suffix);
    return names;
}

namespace {

// The GL the figure was drawn with: its renderer and version, whether that
// is llvmpipe (software, what the goldens are made with) or not (a GPU),
// the platform it came through (--gl), the device for egl-device, the
// samples a pixel of every multisampled canvas, and whether it was a debug
// context (FIGGEN_GL_DEBUG=1).
nlohmann::json renderer_metadata(const render::GlContext& gl) {
    nlohmann::json r = {{"gl_renderer", gl.renderer()},
                        {"gl_version", gl.version()},
                        {"software", render::is_llvmpipe(gl.renderer())},
                        {"platform", gl.platform()},
                        {"samples", render::canvas_samples}};
    if (!gl.device().empty()) r["device"] = gl.device();
    if (gl.debug()) r["debug"] = true;
    return r;
}

}  // namespace

void write_figure(const Description& d, const OutputOptions& options, const base::Folder& folder,
                  const MemoryEstimate& memory, const render::Image& image, nlohmann::json metadata) {
    const auto& gl = render::GlContext::get();
    render::check_gl("the figure");  // in a debug context, what it reported since the last check
    nlohmann::json meta = {
        {"id", d.id},
        {"title", d.title},
        {"source", d.source},
        {"scene", d.scene},
        {"caption", d.caption},
        {"seed", d.seed},
        {"description", d.file.filename().string()},
        {"figgen_version", base::version()},
        {"renderer", renderer_metadata(gl)},
        {"scale", options.scale},
        {"memory_estimate", {{"bytes", std::llround(memory.bytes)}, {"largest", memory.largest.what}}},
    };
    meta.update(metadata);
    meta["image"] = {{"file", d.id + ".png"}, {"size", {image.width, image.height}}};
    if (options.transparent) meta["image"]["transparent"] = true;

    media::write_png(folder, d.id + ".png", image,
                      {{"Title", d.title},
                       {"Source", d.source},
                       {"Software", std::string("figgen ") + base::version()},
                       {"figgen:id", d.id},
                       {"figgen:seed", std::to_string(d.seed)},
                       {"figgen:params", meta.value("params", nlohmann::json::object()).dump()}});
    base::write_file_atomically(folder, d.id + ".json", meta.dump(2) + "\n");
}

}  // namespace app
