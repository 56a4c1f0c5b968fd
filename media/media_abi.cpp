// The media module's C face (media/media_abi.h): each C function turns its
// arguments into media/media.hpp's C++ types, calls the module's own
// implementation (media/ffmpeg.cpp), and hands the results back through
// the caller's buffers and callbacks; every exception becomes an error
// record, so none crosses the boundary.
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "media/media.hpp"
#include "media/media_abi.h"

namespace media::codec {
namespace {

void set_text(char* out, std::size_t size, const std::string& text) {
    std::snprintf(out, size, "%s", text.c_str());
}

// Runs f, turning what it throws into *error; 0, or 1 after an error.
template <class F>
int guard(figgen_media_error* error, F&& f) {
    figgen_media_error e{};
    try {
        f();
        return 0;
    } catch (const ImageTooLarge& x) {
        e.kind = FIGGEN_MEDIA_IMAGE_TOO_LARGE;
        set_text(e.message, sizeof e.message, x.what());
        set_text(e.file, sizeof e.file, x.file);
        e.width = x.width, e.height = x.height, e.max_pixels = x.max_pixels;
    } catch (const std::out_of_range& x) {
        e.kind = FIGGEN_MEDIA_OUT_OF_RANGE;
        set_text(e.message, sizeof e.message, x.what());
    } catch (const std::invalid_argument& x) {
        e.kind = FIGGEN_MEDIA_INVALID_ARGUMENT;
        set_text(e.message, sizeof e.message, x.what());
    } catch (const std::logic_error& x) {
        e.kind = FIGGEN_MEDIA_LOGIC_ERROR;
        set_text(e.message, sizeof e.message, x.what());
    } catch (const std::exception& x) {
        e.kind = FIGGEN_MEDIA_RUNTIME_ERROR;
        set_text(e.message, sizeof e.message, x.what());
    } catch (...) {
        e.kind = FIGGEN_MEDIA_RUNTIME_ERROR;
        set_text(e.message, sizeof e.message, "the media module failed");
    }
    if (error) *error = e;
    return 1;
}

std::string text(const char* s) {
    return s ? s : "";
}

Image image_of(const figgen_media_image* in) {
    if (!in || in->width < 0 || in->height < 0 || (!in->rgba && in->width > 0 && in->height > 0))
        throw std::invalid_argument("an image without its pixels");
    Image image;
    image.width = in->width;
    image.height = in->height;
    image.rgba.assign(in->rgba, in->rgba + static_cast<std::size_t>(in->width) * in->height * 4);
    return image;
}

void give(const Image& image, const figgen_media_image_sink& sink) {
    std::uint8_t* out = sink.pixels ? sink.pixels(sink.context, image.width, image.height) : nullptr;
    if (!out) throw std::runtime_error("no room for a " + std::to_string(image.width) + " x " +
                                       std::to_string(image.height) + " image");
    std::memcpy(out, image.rgba.data(), image.rgba.size());
}

VideoOptions video_options(const figgen_video_options* o) {
    if (!o) throw std::invalid_argument("no video options");
    VideoOptions v;
    v.fps = o->fps;
    v.threads = o->threads;
    v.crf = o->crf;
    v.codec = text(o->codec);
    v.preset = text(o->preset);
    v.tune = text(o->tune);
    v.segment_frames = o->segment_frames;
    v.container = text(o->container);
    v.speed = o->speed;
    return v;
}

PreviewOptions preview_options(const figgen_preview_options* o) {
    if (!o) throw std::invalid_argument("no preview options");
    PreviewOptions p;
    p.max_width = o->max_width;
    p.max_height = o->max_height;
    p.max_frames = o->max_frames;
    p.max_seconds = o->max_seconds;
    p.quality = o->quality;
    p.max_bytes = o->max_bytes;
    return p;
}

void set_info(figgen_preview_info* out, const PreviewInfo& in) {
    if (!out) return;
    *out = {in.frames, in.width, in.height, in.loop_count, in.duration_ms, in.bytes, in.quality};
}

std::vector<Packet> packets_of(const figgen_media_packet* packets, std::size_t count) {
    std::vector<Packet> out;
    out.reserve(count);
    for (std::size_t k = 0; k < count; ++k) {
        Packet p;
        p.data.assign(packets[k].data, packets[k].data + packets[k].size);
        p.pts = packets[k].pts;
        p.dts = packets[k].dts;
        p.key = packets[k].key != 0;
        out.push_back(std::move(p));
    }
    return out;
}

}  // namespace
}  // namespace media::codec

using namespace media::codec;
using render::Image;

struct figgen_media_encoder {
    std::unique_ptr<Encoder> encoder;
    std::string codec;
};
struct figgen_media_segment {
    std::unique_ptr<SegmentEncoder> segment;
};
struct figgen_media_preview {
    std::unique_ptr<PreviewEncoder> preview;
};

namespace {

int open_encoder(int fd, const char* shown, int32_t width, int32_t height, const figgen_video_options* options,
                 figgen_media_encoder** out, figgen_media_error* error) {
    return guard(error, [&] {
        auto e = std::make_unique<figgen_media_encoder>();
        e->encoder = implementation().open_encoder(fd, text(shown), width, height, video_options(options));
        e->codec = e->encoder->codec_name();
        *out = e.release();
    });
}
int encoder_add(figgen_media_encoder* e, const figgen_media_image* frame, figgen_media_error* error) {
    return guard(error, [&] { e->encoder->add(image_of(frame)); });
}
int encoder_add_segment(figgen_media_encoder* e, const figgen_media_packet* packets, size_t count, int32_t frames,
                        figgen_media_error* error) {
    return guard(error, [&] { e->encoder->add_segment(packets_of(packets, count), frames); });
}
int encoder_finish(figgen_media_encoder* e, figgen_media_error* error) {
    return guard(error, [&] { e->encoder->finish(); });
}
const char* encoder_codec(const figgen_media_encoder* e) {
    return e->codec.c_str();
}
void encoder_close(figgen_media_encoder* e) {
    delete e;
}

int open_segment(const char* shown, int32_t width, int32_t height, const figgen_video_options* options,
                 figgen_media_segment** out, figgen_media_error* error) {
    return guard(error, [&] {
        auto s = std::make_unique<figgen_media_segment>();
        s->segment = implementation().open_segment(text(shown), width, height, video_options(options));
        *out = s.release();
    });
}
int segment_add(figgen_media_segment* s, const figgen_media_image* frame, figgen_media_error* error) {
    return guard(error, [&] { s->segment->add(image_of(frame)); });
}
int segment_finish(figgen_media_segment* s, figgen_media_packet_sink sink, figgen_media_error* error) {
    return guard(error, [&] {
        for (const Packet& p : s->segment->finish()) {
            const figgen_media_packet c{p.data.data(), p.data.size(), p.pts, p.dts, p.key};
            sink.packet(sink.context, &c);
        }
    });
}
int segment_preview_frames(figgen_media_segment* s, const figgen_media_packet* packets, size_t count,
                           const int32_t* indices, size_t index_count, const figgen_preview_options* options,
                           figgen_media_image_sink sink, figgen_media_error* error) {
    return guard(error, [&] {
        const std::vector<int> wanted(indices, indices + index_count);
        for (const Image& frame :
             s->segment->preview_frames(packets_of(packets, count), wanted, preview_options(options)))
            give(frame, sink);
    });
}
void segment_close(figgen_media_segment* s) {
    delete s;
}

int open_preview(const char* shown, int32_t film_frames, int32_t film_fps, const figgen_preview_options* options,
                 figgen_media_preview** out, figgen_media_error* error) {
    return guard(error, [&] {
        auto p = std::make_unique<figgen_media_preview>();
        p->preview = implementation().open_preview(text(shown), film_frames, film_fps, preview_options(options));
        *out = p.release();
    });
}
int preview_add(figgen_media_preview* p, const figgen_media_image* frame, figgen_media_error* error) {
    return guard(error, [&] { p->preview->add(image_of(frame)); });
}
int preview_write(figgen_media_preview* p, int fd, const char* shown, const figgen_media_image* frames, size_t count,
                  figgen_preview_info* info, figgen_media_error* error) {
    return guard(error, [&] {
        std::vector<Image> kept;
        kept.reserve(count);
        for (std::size_t k = 0; k < count; ++k) kept.push_back(image_of(&frames[k]));
        set_info(info, p->preview->write(fd, text(shown), kept));
    });
}
void preview_close(figgen_media_preview* p) {
    delete p;
}

int probe_video(const char* path, figgen_video_info* info, figgen_media_error* error) {
    return guard(error, [&] {
        thread_local media::VideoInfo held;
        held = implementation().probe_video(text(path));
        *info = {held.frames,        held.width,           held.height,
                 held.pixel_format.c_str(), held.codec.c_str(), held.duration_seconds,
                 held.fps,           held.key_frames.data(), held.key_frames.size()};
    });
}
int decode_frame(const char* path, int32_t index, int32_t threads, figgen_media_image_sink sink,
                 figgen_media_error* error) {
    return guard(error, [&] { give(implementation().decode_frame(text(path), index, threads), sink); });
}
int scale(const figgen_media_image* image, int32_t width, int32_t height, figgen_media_image_sink sink,
          figgen_media_error* error) {
    return guard(error, [&] { give(implementation().scale(image_of(image), width, height), sink); });
}
int write_preview(int fd, const char* shown, int film_fd, int32_t film_frames, int32_t film_fps,
                  const figgen_preview_options* options, figgen_preview_info* info, figgen_media_error* error) {
    return guard(error, [&] {
        set_info(info, implementation().write_preview(fd, text(shown), film_fd, film_frames, film_fps,
                                                      preview_options(options)));
    });
}
int probe_preview(const char* path, figgen_preview_info* info, figgen_media_error* error) {
    return guard(error, [&] { set_info(info, implementation().probe_preview(text(path))); });
}
int write_webm(int fd, const char* shown, int film_fd, int32_t fps, const figgen_webm_options* options,
               uint64_t* bytes, figgen_media_error* error) {
    return guard(error, [&] {
        if (!options) throw std::invalid_argument("no WebM options");
        media::WebmOptions webm;
        webm.crf = options->crf;
        webm.speed = options->speed;
        *bytes = implementation().write_webm(fd, text(shown), film_fd, fps, webm);
    });
}
int decode_preview_frame(const char* path, int32_t index, figgen_media_image_sink sink, figgen_media_error* error) {
    return guard(error, [&] { give(implementation().decode_preview_frame(text(path), index), sink); });
}
int write_preview_thumbnail(int fd, const char* shown, int source_fd, const char* source, uint64_t max_pixels,
                            const figgen_preview_options* options, figgen_preview_info* info,
                            figgen_media_error* error) {
    return guard(error, [&] {
        set_info(info, implementation().write_preview_thumbnail(fd, text(shown), source_fd, text(source), max_pixels,
                                                                preview_options(options)));
    });
}
int decode_film_frame(int fd, const char* shown, int32_t index, int32_t threads, uint64_t max_pixels,
                      figgen_media_image_sink sink, figgen_media_error* error) {
    return guard(error, [&] {
        give(implementation().decode_film_frame(fd, text(shown), index, threads, max_pixels), sink);
    });
}
int webp_canvas(int fd, const char* shown, figgen_preview_info* info, figgen_media_error* error) {
    return guard(error, [&] { set_info(info, implementation().webp_canvas(fd, text(shown))); });
}

const figgen_media_api functions{.version = FIGGEN_MEDIA_ABI_VERSION,
                                  .open_encoder = open_encoder,
                                  .encoder_add = encoder_add,
                                  .encoder_add_segment = encoder_add_segment,
                                  .encoder_finish = encoder_finish,
                                  .encoder_codec = encoder_codec,
                                  .encoder_close = encoder_close,
                                  .open_segment = open_segment,
                                  .segment_add = segment_add,
                                  .segment_finish = segment_finish,
                                  .segment_preview_frames = segment_preview_frames,
                                  .segment_close = segment_close,
                                  .open_preview = open_preview,
                                  .preview_add = preview_add,
                                  .preview_write = preview_write,
                                  .preview_close = preview_close,
                                  .probe_video = probe_video,
                                  .decode_frame = decode_frame,
                                  .scale = scale,
                                  .write_preview = write_preview,
                                  .probe_preview = probe_preview,
                                  .write_webm = write_webm,
                                  .decode_preview_frame = decode_preview_frame,
                                  .write_preview_thumbnail = write_preview_thumbnail,
                                  .decode_film_frame = decode_film_frame,
                                  .webp_canvas = webp_canvas};

}  // namespace

extern "C" const figgen_media_api* figgen_media_module(void) {
    return &functions;
}
