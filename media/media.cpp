// The program's side of the media module: media/media.hpp's Api, each call
// made through the module's plain C interface (media/media_abi.h) and its
// error record thrown again as the exception it stands for.
#include "media/media.hpp"

#include <cstring>
#include <stdexcept>

#include "base/module.hpp"
#include "media/media_abi.h"

namespace media::codec {
namespace {

constexpr base::ModuleSpec spec{FIGGEN_MEDIA_RELATIVE,
                                FIGGEN_MEDIA_BUILT,
                                "figgen_media_module",
                                FIGGEN_MEDIA_ABI_VERSION,
                                "video module",
                                "libavcodec59, libavformat59 and libswscale6"};

const figgen_media_api& c_api() {
    return base::module_of<figgen_media_api, spec>().api();
}

// Throws what the module's call failed with (0: nothing).
void check(int status, const figgen_media_error& e) {
    if (status == 0) return;
    switch (e.kind) {
        case FIGGEN_MEDIA_IMAGE_TOO_LARGE: throw ImageTooLarge(e.file, e.width, e.height, e.max_pixels);
        case FIGGEN_MEDIA_OUT_OF_RANGE: throw std::out_of_range(e.message);
        case FIGGEN_MEDIA_INVALID_ARGUMENT: throw std::invalid_argument(e.message);
        case FIGGEN_MEDIA_LOGIC_ERROR: throw std::logic_error(e.message);
        default: throw std::runtime_error(e.message[0] ? e.message : "the video module failed");
    }
}

figgen_media_image view(const Image& image) {
    return {image.width, image.height, image.rgba.data()};
}

// The module's images, each written straight into an Image of ours.
struct Images {
    std::vector<Image> images;
    figgen_media_image_sink sink() {
        return {this, [](void* context, int32_t width, int32_t height) -> uint8_t* {
                    if (width < 0 || height < 0) return nullptr;
                    auto& self = *static_cast<Images*>(context);
                    Image& image = self.images.emplace_back();
                    image.width = width;
                    image.height = height;
                    image.rgba.assign(static_cast<std::size_t>(width) * height * 4, 0);
                    return image.rgba.data();
                }};
    }
    Image one() {
        if (images.size() != 1) throw std::runtime_error("the video module gave no image");
        return std::move(images.front());
    }
};

// Options in C: the strings point into `o`, which must outlive the call.
figgen_video_options c_options(const VideoOptions& o) {
    return {o.fps,
            o.threads,
            o.crf,
            o.codec.c_str(),
            o.preset.c_str(),
            o.tune.c_str(),
            o.segment_frames,
            o.container.c_str(),
            o.speed};
}
figgen_preview_options c_options(const PreviewOptions& o) {
    return {o.max_width, o.max_height, o.max_frames, o.max_seconds, o.quality, o.max_bytes};
}
PreviewInfo info_of(const figgen_preview_info& i) {
    PreviewInfo info;
    info.frames = i.frames;
    info.width = i.width;
    info.height = i.height;
    info.loop_count = i.loop_count;
    info.duration_ms = i.duration_ms;
    info.bytes = i.bytes;
    info.quality = i.quality;
    return info;
}
std::vector<figgen_media_packet> c_packets(const std::vector<Packet>& packets) {
    std::vector<figgen_media_packet> out;
    out.reserve(packets.size());
    for (const Packet& p : packets) out.push_back({p.data.data(), p.data.size(), p.pts, p.dts, p.key});
    return out;
}

class CEncoder final : public Encoder {
public:
    explicit CEncoder(figgen_media_encoder* e) : e_(e), codec_(c_api().encoder_codec(e)) {}
    ~CEncoder() override { c_api().encoder_close(e_); }
    void add(const Image& frame) override {
        figgen_media_error error;
        const figgen_media_image v = view(frame);
        check(c_api().encoder_add(e_, &v, &error), error);
    }
    void add_segment(const std::vector<Packet>& packets, int frames) override {
        figgen_media_error error;
        const std::vector<figgen_media_packet> c = c_packets(packets);
        check(c_api().encoder_add_segment(e_, c.data(), c.size(), frames, &error), error);
    }
    void finish() override {
        figgen_media_error error;
        check(c_api().encoder_finish(e_, &error), error);
    }
    std::string codec_name() const override { return codec_; }

private:
    figgen_media_encoder* e_;
    std::string codec_;
};

class CSegment final : public SegmentEncoder {
public:
    explicit CSegment(figgen_media_segment* s) : s_(s) {}
    ~CSegment() override { c_api().segment_close(s_); }
    void add(const Image& frame) override {
        figgen_media_error error;
        const figgen_media_image v = view(frame);
        check(c_api().segment_add(s_, &v, &error), error);
    }
    std::vector<Packet> finish() override {
        std::vector<Packet> packets;
        const figgen_media_packet_sink sink{
            &packets, [](void* context, const figgen_media_packet* p) {
                Packet packet;
                packet.data.assign(p->data, p->data + p->size);
                packet.pts = p->pts;
                packet.dts = p->dts;
                packet.key = p->key != 0;
                static_cast<std::vector<Packet>*>(context)->push_back(std::move(packet));
            }};
        figgen_media_error error;
        check(c_api().segment_finish(s_, sink, &error), error);
        return packets;
    }
    std::vector<Image> preview_frames(const std::vector<Packet>& packets, const std::vector<int>& indices,
                                      const PreviewOptions& options) override {
        const std::vector<figgen_media_packet> c = c_packets(packets);
        const std::vector<int32_t> wanted(indices.begin(), indices.end());
        const figgen_preview_options o = c_options(options);
        Images images;
        figgen_media_error error;
        check(c_api().segment_preview_frames(s_, c.data(), c.size(), wanted.data(), wanted.size(), &o, images.sink(),
                                             &error),
              error);
        return std::move(images.images);
    }

private:
    figgen_media_segment* s_;
};

class CPreview final : public PreviewEncoder {
public:
    explicit CPreview(figgen_media_preview* p) : p_(p) {}
    ~CPreview() override { c_api().preview_close(p_); }
    void add(const Image& frame) override {
        figgen_media_error error;
        const figgen_media_image v = view(frame);
        check(c_api().preview_add(p_, &v, &error), error);
    }
    PreviewInfo write(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames) override {
        std::vector<figgen_media_image> views;
        views.reserve(frames.size());
        for (const Image& f : frames) views.push_back(view(f));
        figgen_preview_info info{};
        figgen_media_error error;
        check(c_api().preview_write(p_, fd, shown.c_str(), views.data(), views.size(), &info, &error), error);
        return info_of(info);
    }

private:
    figgen_media_preview* p_;
};

std::unique_ptr<Encoder> open_encoder(int fd, const std::filesystem::path& shown, int width, int height,
                                      const VideoOptions& options) {
    const figgen_video_options o = c_options(options);
    figgen_media_encoder* e = nullptr;
    figgen_media_error error;
    check(c_api().open_encoder(fd, shown.c_str(), width, height, &o, &e, &error), error);
    return std::make_unique<CEncoder>(e);
}

std::unique_ptr<SegmentEncoder> open_segment(const std::filesystem::path& shown, int width, int height,
                                             const VideoOptions& options) {
    const figgen_video_options o = c_options(options);
    figgen_media_segment* s = nullptr;
    figgen_media_error error;
    check(c_api().open_segment(shown.c_str(), width, height, &o, &s, &error), error);
    return std::make_unique<CSegment>(s);
}

VideoInfo probe_video(const std::filesystem::path& path) {
    figgen_video_info i{};
    figgen_media_error error;
    check(c_api().probe_video(path.c_str(), &i, &error), error);
    VideoInfo info;
    info.frames = i.frames;
    info.width = i.width;
    info.height = i.height;
    info.pixel_format = i.pixel_format ? i.pixel_format : "";
    info.codec = i.codec ? i.codec : "";
    info.duration_seconds = i.duration_seconds;
    info.fps = i.fps;
    info.key_frames.assign(i.key_frames, i.key_frames + i.key_frame_count);
    return info;
}

Image decode_frame(const std::filesystem::path& path, int index, int threads) {
    Images images;
    figgen_media_error error;
    check(c_api().decode_frame(path.c_str(), index, threads, images.sink(), &error), error);
    return images.one();
}

Image scale(const Image& image, int width, int height) {
    Images images;
    const figgen_media_image v = view(image);
    figgen_media_error error;
    check(c_api().scale(&v, width, height, images.sink(), &error), error);
    return images.one();
}

PreviewInfo write_preview(int fd, const std::filesystem::path& shown, int film_fd, int film_frames, int film_fps,
                          const PreviewOptions& options) {
    const figgen_preview_options o = c_options(options);
    figgen_preview_info info{};
    figgen_media_error error;
    check(c_api().write_preview(fd, shown.c_str(), film_fd, film_frames, film_fps, &o, &info, &error), error);
    return info_of(info);
}

PreviewInfo probe_preview(const std::filesystem::path& path) {
    figgen_preview_info info{};
    figgen_media_error error;
    check(c_api().probe_preview(path.c_str(), &info, &error), error);
    return info_of(info);
}

std::unique_ptr<PreviewEncoder> open_preview(const std::filesystem::path& shown, int film_frames, int film_fps,
                                             const PreviewOptions& options) {
    const figgen_preview_options o = c_options(options);
    figgen_media_preview* p = nullptr;
    figgen_media_error error;
    check(c_api().open_preview(shown.c_str(), film_frames, film_fps, &o, &p, &error), error);
    return std::make_unique<CPreview>(p);
}

std::uint64_t write_webm(int fd, const std::filesystem::path& shown, int film_fd, int fps, const WebmOptions& options) {
    const figgen_webm_options o{options.crf, options.speed};
    std::uint64_t bytes = 0;
    figgen_media_error error;
    check(c_api().write_webm(fd, shown.c_str(), film_fd, fps, &o, &bytes, &error), error);
    return bytes;
}

Image decode_preview_frame(const std::filesystem::path& path, int index) {
    Images images;
    figgen_media_error error;
    check(c_api().decode_preview_frame(path.c_str(), index, images.sink(), &error), error);
    return images.one();
}

PreviewInfo write_preview_thumbnail(int fd, const std::filesystem::path& shown, int source_fd,
                                    const std::filesystem::path& source, std::uint64_t max_pixels,
                                    const PreviewOptions& options) {
    const figgen_preview_options o = c_options(options);
    figgen_preview_info info{};
    figgen_media_error error;
    check(c_api().write_preview_thumbnail(fd, shown.c_str(), source_fd, source.c_str(), max_pixels, &o, &info, &error),
          error);
    return info_of(info);
}

Image decode_film_frame(int fd, const std::filesystem::path& shown, int index, int threads, std::uint64_t max_pixels) {
    Images images;
    figgen_media_error error;
    check(c_api().decode_film_frame(fd, shown.c_str(), index, threads, max_pixels, images.sink(), &error), error);
    return images.one();
}

PreviewInfo webp_canvas(int fd, const std::filesystem::path& shown) {
    figgen_preview_info info{};
    figgen_media_error error;
    check(c_api().webp_canvas(fd, shown.c_str(), &info, &error), error);
    return info_of(info);
}

const Api functions{open_encoder, open_segment,         probe_video,  decode_frame,
                    scale,        write_preview,        probe_preview, open_preview,
                    write_webm,   decode_preview_frame, write_preview_thumbnail,
                    decode_film_frame, webp_canvas};

}  // namespace

const Api& api() {
    c_api();  // opens the module, or throws the one line saying why not
    return functions;
}
void preload() {
    base::module_of<figgen_media_api, spec>().preload();
}

}  // namespace media::codec
