// libfiggen_media.so: everything of figgen that FFmpeg does (media/media.hpp).
// Opened by the program when it first encodes, decodes or scales; links
// libavcodec, libavformat, libavutil and libswscale, and nothing of figgen's
// own libraries (the program's AtomicFile opens the files it writes).
#include <malloc.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "media/media.hpp"
#include "media/webp.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/log.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

namespace media::codec {
namespace {

// Owning pointers for the FFmpeg objects, so every exit path frees them.
struct FreeCodec {
    void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FreeFrame {
    void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct FreePacket {
    void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct FreeScaler {
    void operator()(SwsContext* s) const { sws_freeContext(s); }
};
struct FreeParameters {
    void operator()(AVCodecParameters* p) const { avcodec_parameters_free(&p); }
};
// Our own I/O on the temporary's descriptor (AtomicFile), never a path: a
// context of this kind is freed with close_file_io, not avio_close.
struct FileIo {
    int fd;
    std::int64_t position = 0;
};

int read_file_io(void* opaque, std::uint8_t* buffer, int size) {
    auto* io = static_cast<FileIo*>(opaque);
    const ssize_t n = ::pread(io->fd, buffer, static_cast<std::size_t>(size), io->position);
    if (n < 0) return AVERROR(errno);
    if (n == 0) return AVERROR_EOF;
    io->position += n;
    return static_cast<int>(n);
}

int write_file_io(void* opaque, std::uint8_t* buffer, int size) {
    auto* io = static_cast<FileIo*>(opaque);
    for (int written = 0; written < size;) {
        const ssize_t n = ::pwrite(io->fd, buffer + written, static_cast<std::size_t>(size - written), io->position);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return AVERROR(errno);
        written += static_cast<int>(n);
        io->position += n;
    }
    return size;
}

std::int64_t seek_file_io(void* opaque, std::int64_t offset, int whence) {
    auto* io = static_cast<FileIo*>(opaque);
    if (whence & AVSEEK_SIZE) {
        struct stat st {};
        return ::fstat(io->fd, &st) == 0 ? st.st_size : AVERROR(errno);
    }
    switch (whence & ~AVSEEK_FORCE) {
        case SEEK_SET:
            io->position = offset;
            break;
        case SEEK_CUR:
            io->position += offset;
            break;
        case SEEK_END: {
            struct stat st {};
            if (::fstat(io->fd, &st) != 0) return AVERROR(errno);
            io->position = st.st_size + offset;
            break;
        }
        default:
            return AVERROR(EINVAL);
    }
    return io->position;
}

AVIOContext* open_file_io(int fd, bool write) {
    constexpr int size = 1 << 16;
    auto* buffer = static_cast<unsigned char*>(av_malloc(size));
    if (!buffer) return nullptr;
    AVIOContext* context = avio_alloc_context(buffer, size, write ? 1 : 0, new FileIo{fd}, read_file_io,
                                              write ? write_file_io : nullptr, seek_file_io);
    if (!context) av_free(buffer);
    return context;
}

// Flushes (when writing) and frees; returns the first error seen.
int close_file_io(AVIOContext** context) {
    if (!*context) return 0;
    if ((*context)->write_flag) avio_flush(*context);
    const int error = (*context)->error;
    delete static_cast<FileIo*>((*context)->opaque);
    av_freep(&(*context)->buffer);
    avio_context_free(context);
    return error;
}

// The muxer reopens its own output to move the index to the front
// (faststart): give it the same file, never the path.
int reopen_output(AVFormatContext* format, AVIOContext** context, const char* /*url*/, int flags,
                  AVDictionary** /*options*/) {
    if (flags & AVIO_FLAG_WRITE) return AVERROR(EPERM);
    *context = open_file_io(static_cast<FileIo*>(format->pb->opaque)->fd, false);
    return *context ? 0 : AVERROR(ENOMEM);
}

int close_reopened(AVFormatContext* /*format*/, AVIOContext* context) {
    return close_file_io(&context);
}

struct CloseOutput {
    void operator()(AVFormatContext* f) const {
        close_file_io(&f->pb);
        avformat_free_context(f);
    }
};
struct CloseInput {
    void operator()(AVFormatContext* f) const { avformat_close_input(&f); }
};
using CodecPtr = std::unique_ptr<AVCodecContext, FreeCodec>;
using FramePtr = std::unique_ptr<AVFrame, FreeFrame>;
using PacketPtr = std::unique_ptr<AVPacket, FreePacket>;
using ScalerPtr = std::unique_ptr<SwsContext, FreeScaler>;
using ParametersPtr = std::unique_ptr<AVCodecParameters, FreeParameters>;
using OutputPtr = std::unique_ptr<AVFormatContext, CloseOutput>;
using InputPtr = std::unique_ptr<AVFormatContext, CloseInput>;

// Errors become exceptions carrying av_strerror's text, so FFmpeg's own log
// would only repeat them (and x264 chats at info level): silence it, once.
void quiet_ffmpeg() {
    static const bool quiet = (av_log_set_level(AV_LOG_QUIET), true);
    (void)quiet;
}

// One line: "cannot write out/a.mp4: writing a packet: No space left on device".
[[noreturn]] void fail(const char* verb, const std::filesystem::path& path, const char* step, int err) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av_strerror(err, text, sizeof text);
    throw std::runtime_error(std::string("cannot ") + verb + " " + path.string() + ": " + step + ": " + text);
}

// FFmpeg reads "a:b.mp4" as protocol "a"; the explicit protocol keeps any
// file name a file name.
std::string file_url(const std::filesystem::path& path) {
    return "file:" + path.string();
}

// The RGB <-> YUV matrix the writer uses and tags the stream with: BT.709,
// what players assume for HD and the primaries sRGB shares.
constexpr int kMatrix = SWS_CS_ITU709;

const AVCodec* find_encoder(const std::string& name) {
    if (name == "auto") {
        if (const AVCodec* x264 = avcodec_find_encoder_by_name("libx264")) return x264;
        return avcodec_find_encoder(AV_CODEC_ID_MPEG4);
    }
    if (name == "libx264") return avcodec_find_encoder_by_name("libx264");
    if (name == "mpeg4") return avcodec_find_encoder(AV_CODEC_ID_MPEG4);
    if (name == "libvpx-vp9") return avcodec_find_encoder_by_name("libvpx-vp9");
    throw std::invalid_argument("video codec \"" + name + "\" is not allowed: use auto, libx264 or mpeg4");
}

// An encoder of `codec` with figgen's settings; `global_header` for a
// muxer that keeps the stream's headers apart (MP4). Errors name `shown`.
CodecPtr open_codec(const AVCodec* codec, const std::filesystem::path& shown, int width, int height,
                    const VideoOptions& options, bool global_header) {
    CodecPtr context(avcodec_alloc_context3(codec));
    if (!context) fail("write", shown, "creating the encoder", AVERROR(ENOMEM));
    AVCodecContext& c = *context;
    c.width = width;
    c.height = height;
    c.pix_fmt = AV_PIX_FMT_YUV420P;  // the one format every player decodes
    c.sample_aspect_ratio = {1, 1};
    c.time_base = {1, options.fps};  // pts = frame index
    c.framerate = {options.fps, 1};
    c.thread_count = options.threads;
    c.gop_size = 10 * options.fps;      // a keyframe every 10 s for seeking; mpeg4's default of 12 wastes bits
    c.flags |= AV_CODEC_FLAG_BITEXACT;  // no encoder version string in the stream (mpeg4)
    if (global_header) c.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    c.color_range = AVCOL_RANGE_MPEG;
    c.color_primaries = AVCOL_PRI_BT709;
    c.color_trc = AVCOL_TRC_BT709;
    c.colorspace = AVCOL_SPC_BT709;

    AVDictionary* codec_options = nullptr;
    if (std::string(codec->name) == "libx264") {
        av_dict_set(&codec_options, "crf", std::to_string(options.crf).c_str(), 0);
        // Pinned like the threads: it shapes the bytes.
        av_dict_set(&codec_options, "preset", options.preset.c_str(), 0);
        if (!options.tune.empty()) av_dict_set(&codec_options, "tune", options.tune.c_str(), 0);
    } else if (std::string(codec->name) == "libvpx-vp9") {
        // Constant quality: crf with no bitrate target.
        c.bit_rate = 0;
        av_dict_set(&codec_options, "crf", std::to_string(options.crf).c_str(), 0);
        av_dict_set(&codec_options, "deadline", options.speed >= 6 ? "realtime" : "good", 0);
        av_dict_set(&codec_options, "cpu-used", std::to_string(options.speed).c_str(), 0);
        av_dict_set(&codec_options, "row-mt", "0", 0);  // one thread, as the threads above: the same bytes
    } else {
        // Fixed quantiser: crf 18 -> qscale 3, about as transparent as x264 at crf 18.
        const int qscale = std::clamp((options.crf + 3) / 6, 1, 31);
        c.flags |= AV_CODEC_FLAG_QSCALE;
        c.global_quality = FF_QP2LAMBDA * qscale;
    }
    const int opened = avcodec_open2(&c, codec, &codec_options);
    av_dict_free(&codec_options);
    if (opened < 0) fail("write", shown, "opening the encoder", opened);
    return context;
}

const AVCodec* chosen_codec(const std::filesystem::path& shown, const VideoOptions& options) {
    const AVCodec* codec = find_encoder(options.codec);
    if (!codec)
        throw std::runtime_error("cannot write " + shown.string() + ": FFmpeg has no " + options.codec + " encoder");
    return codec;
}

// libx264 reads memory it allocated but never wrote: in a fresh process
// that is zero, but after other work it holds whatever was freed there,
// and a film's bytes then depend on what its process did before (seen
// under mpirun, where a rank encodes segments of several films, and in one
// process encoding the same frames twice under load; found with glibc's
// MALLOC_PERTURB_, which made the bytes repeat; mpeg4 never differs). While
// an encoder exists, from its opening to its end (x264's own threads
// allocate in between, not only inside our calls), glibc fills every fresh
// allocation with one byte (M_PERTURB), so x264's stray reads see the same
// bytes in every process. Nested and concurrent encoders share the switch.
class SameFreshMemory {
public:
    SameFreshMemory() {
        std::lock_guard<std::mutex> hold(lock());
        if (depth()++ == 0) mallopt(M_PERTURB, fill);
    }
    ~SameFreshMemory() {
        std::lock_guard<std::mutex> hold(lock());
        if (--depth() == 0) mallopt(M_PERTURB, 0);
    }
    SameFreshMemory(const SameFreshMemory&) = delete;
    SameFreshMemory& operator=(const SameFreshMemory&) = delete;

private:
    static constexpr int fill = 0x55;
    static std::mutex& lock() {
        static std::mutex m;
        return m;
    }
    static int& depth() {
        static int d = 0;
        return d;
    }
};

// Zeroes a frame's whole buffers, padding included: the encoder's SIMD
// loads may reach past the picture into the padded line.
void clear_buffers(AVFrame& frame) {
    for (AVBufferRef* buffer : frame.buf)
        if (buffer) std::memset(buffer->data, 0, buffer->size);
}

Image to_rgba(const AVFrame* frame, const std::filesystem::path& shown);
Image fitted(const Image& frame, const PreviewOptions& options);

// One segment of a film: a fresh encoder, so the segment starts with a key
// frame and no frame of it refers to a frame outside it (a closed group of
// pictures). Its packets join the others' by stream copy.
class FfmpegSegment final : public SegmentEncoder {
public:
    FfmpegSegment(const std::filesystem::path& shown, int width, int height, const VideoOptions& options)
        : shown_(shown), width_(width), height_(height) {
        quiet_ffmpeg();
        codec_ = open_codec(chosen_codec(shown, options), shown, width, height, options, true);
        yuv_.reset(av_frame_alloc());
        packet_.reset(av_packet_alloc());
        if (!yuv_ || !packet_) fail_write("allocating a frame", AVERROR(ENOMEM));
        yuv_->format = codec_->pix_fmt;
        yuv_->width = width_;
        yuv_->height = height_;
        check(av_frame_get_buffer(yuv_.get(), 0), "allocating a frame");
        clear_buffers(*yuv_);
        // FULL_CHR_H_INP: filter the chroma from every RGB pixel rather than
        // subsampling first; ACCURATE_RND and BITEXACT: same bytes on every CPU.
        scaler_.reset(sws_getContext(width_, height_, AV_PIX_FMT_RGBA, width_, height_, AV_PIX_FMT_YUV420P,
                                     SWS_BICUBIC | SWS_FULL_CHR_H_INP | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
                                     nullptr, nullptr));
        if (!scaler_) fail_write("creating the colour converter", AVERROR(EINVAL));
        // Full-range RGB in, limited-range BT.709 out, matching the stream's tags.
        const int* matrix = sws_getCoefficients(kMatrix);
        if (sws_setColorspaceDetails(scaler_.get(), matrix, 1, matrix, 0, 0, 1 << 16, 1 << 16) < 0)
            fail_write("configuring the colour converter", AVERROR(EINVAL));
    }

    void add(const Image& frame) override {
        // The encoder may still hold the previous frame's buffer (mpeg4 does).
        const std::uint8_t* before = yuv_->data[0];
        check(av_frame_make_writable(yuv_.get()), "allocating a frame");
        if (yuv_->data[0] != before) clear_buffers(*yuv_);  // a new buffer: cleared as the first
        const std::uint8_t* const planes[] = {frame.rgba.data()};
        const int strides[] = {width_ * 4};
        sws_scale(scaler_.get(), planes, strides, 0, height_, yuv_->data, yuv_->linesize);
        yuv_->pts = frames_++;
        check(avcodec_send_frame(codec_.get(), yuv_.get()), "encoding a frame");
        drain();
    }

    std::vector<Packet> finish() override {
        check(avcodec_send_frame(codec_.get(), nullptr), "flushing the encoder");  // x264 holds frames back
        drain();
        // The stream's parameters (its headers) kept for preview_frames; the
        // encoder and its frames go now.
        parameters_.reset(avcodec_parameters_alloc());
        if (!parameters_) fail_write("keeping the stream's parameters", AVERROR(ENOMEM));
        check(avcodec_parameters_from_context(parameters_.get(), codec_.get()), "keeping the stream's parameters");
        codec_.reset();
        scaler_.reset();
        yuv_.reset();
        return std::move(packets_);
    }

    std::vector<Image> preview_frames(const std::vector<Packet>& packets, const std::vector<int>& indices,
                                      const PreviewOptions& options) override {
        if (!parameters_) throw std::logic_error("preview_frames before finish");
        std::vector<Image> kept;
        if (indices.empty()) return kept;
        const AVCodec* codec = avcodec_find_decoder(parameters_->codec_id);
        if (!codec) fail_read("finding its decoder", AVERROR_DECODER_NOT_FOUND);
        CodecPtr decoder(avcodec_alloc_context3(codec));
        FramePtr frame(av_frame_alloc());
        if (!decoder || !frame) fail_read("allocating the decoder", AVERROR(ENOMEM));
        check_read(avcodec_parameters_to_context(decoder.get(), parameters_.get()), "configuring the decoder");
        decoder->thread_count = 1;  // this is a worker thread already
        check_read(avcodec_open2(decoder.get(), codec, nullptr), "opening the decoder");
        // A frame's presentation time is its index in the segment. Frames
        // no other frame refers to are skipped unless wanted (the others
        // decode the same without them).
        const auto wanted = [&](std::int64_t pts) { return std::binary_search(indices.begin(), indices.end(), pts); };
        std::size_t next = 0;
        const auto receive = [&] {
            for (;;) {
                const int ret = avcodec_receive_frame(decoder.get(), frame.get());
                if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
                check_read(ret, "decoding a frame");
                if (next < indices.size() && frame->pts == indices[next]) {
                    kept.push_back(fitted(to_rgba(frame.get(), shown_), options));
                    ++next;
                }
                av_frame_unref(frame.get());
            }
        };
        for (const Packet& p : packets) {
            check_read(av_new_packet(packet_.get(), static_cast<int>(p.data.size())), "reading a packet");
            std::copy(p.data.begin(), p.data.end(), packet_->data);
            packet_->pts = p.pts;
            packet_->dts = p.dts;
            if (p.key) packet_->flags |= AV_PKT_FLAG_KEY;
            decoder->skip_frame = wanted(p.pts) ? AVDISCARD_DEFAULT : AVDISCARD_NONREF;
            const int sent = avcodec_send_packet(decoder.get(), packet_.get());
            av_packet_unref(packet_.get());
            check_read(sent, "decoding a packet");
            receive();
            if (next == indices.size()) return kept;
        }
        check_read(avcodec_send_packet(decoder.get(), nullptr), "flushing the decoder");
        receive();
        if (next != indices.size()) fail_read("decoding its frames back", AVERROR_INVALIDDATA);
        return kept;
    }

    int frames() const { return static_cast<int>(frames_); }

private:
    [[noreturn]] void fail_write(const char* step, int err) const { fail("write", shown_, step, err); }
    [[noreturn]] void fail_read(const char* step, int err) const { fail("read", shown_, step, err); }
    void check(int ret, const char* step) const {
        if (ret < 0) fail_write(step, ret);
    }
    void check_read(int ret, const char* step) const {
        if (ret < 0) fail_read(step, ret);
    }
    void drain() {
        for (;;) {
            const int ret = avcodec_receive_packet(codec_.get(), packet_.get());
            if (ret == AVERROR(EAGAIN) || ret == AVERROR_EOF) return;
            check(ret, "encoding a frame");
            packets_.push_back({std::vector<std::uint8_t>(packet_->data, packet_->data + packet_->size), packet_->pts,
                                packet_->dts, (packet_->flags & AV_PKT_FLAG_KEY) != 0});
            av_packet_unref(packet_.get());
        }
    }

    SameFreshMemory same_;  // first: on before the encoder opens, off after it is freed
    std::filesystem::path shown_;
    int width_, height_;
    std::int64_t frames_ = 0;
    CodecPtr codec_;
    ScalerPtr scaler_;
    FramePtr yuv_;
    PacketPtr packet_;
    std::vector<Packet> packets_;
    ParametersPtr parameters_;  // after finish()
};

// A film into an MP4 on a file descriptor: frames are encoded in segments
// of options.segment_frames (FfmpegSegment), or segments come encoded
// (add_segment, from other processes); both are written by stream copy.
class FfmpegEncoder final : public Encoder {
public:
    FfmpegEncoder(int fd, const std::filesystem::path& shown, int width, int height, const VideoOptions& options)
        : shown_(shown), width_(width), height_(height), options_(options) {
        quiet_ffmpeg();
        const AVCodec* codec = chosen_codec(shown, options);
        codec_name_ = codec->name;
        open(fd, codec);
    }

    void add(const Image& frame) override {
        if (!segment_) segment_ = std::make_unique<FfmpegSegment>(shown_, width_, height_, options_);
        segment_->add(frame);
        if (options_.segment_frames > 0 && segment_->frames() == options_.segment_frames) end_segment();
    }

    void add_segment(const std::vector<Packet>& packets, int frames) override {
        if (segment_) end_segment();
        write(packets);
        first_frame_ += frames;
    }

    void finish() override {
        if (segment_) end_segment();
        // The trailer moves the index to the front (faststart) by rewriting the file.
        check(av_write_trailer(format_.get()), "writing the trailer");
        check(format_->pb->error, "writing the file");
        // Closing flushes the last buffer: a full disk may show up only here.
        check(close_file_io(&format_->pb), "closing the file");
    }

    std::string codec_name() const override { return codec_name_; }

private:
    void open(int fd, const AVCodec* codec) {
        // The file is ours (custom I/O), so the muxer is named, not guessed.
        AVFormatContext* format = nullptr;
        check(avformat_alloc_output_context2(&format, nullptr, options_.container.c_str(), nullptr),
              "creating the muxer");
        format_.reset(format);
        format->flags |= AVFMT_FLAG_CUSTOM_IO;
        format->io_open = reopen_output;
        format->io_close2 = close_reopened;
        format->flags |= AVFMT_FLAG_BITEXACT;  // no "Lavf" version string in the file
        stream_ = avformat_new_stream(format, nullptr);
        if (!stream_) fail_write("creating the stream", AVERROR(ENOMEM));
        // The stream's parameters (its headers) from an encoder of the same
        // settings: every segment's encoder makes the same ones.
        const CodecPtr c =
            open_codec(codec, shown_, width_, height_, options_, (format->oformat->flags & AVFMT_GLOBALHEADER) != 0);
        time_base_ = c->time_base;
        check(avcodec_parameters_from_context(stream_->codecpar, c.get()), "configuring the stream");
        stream_->time_base = c->time_base;
        stream_->avg_frame_rate = c->framerate;

        format->pb = open_file_io(fd, true);
        if (!format->pb) fail_write("opening the file", AVERROR(ENOMEM));
        AVDictionary* muxer_options = nullptr;
        // No creation_time is set, so the header carries none: same frames, same bytes.
        if (options_.container == "mp4")
            av_dict_set(&muxer_options, "movflags", "+faststart", 0);  // index first: playable while downloading
        const int header = avformat_write_header(format, &muxer_options);
        av_dict_free(&muxer_options);
        check(header, "writing the header");
        packet_.reset(av_packet_alloc());
        if (!packet_) fail_write("allocating a packet", AVERROR(ENOMEM));
    }

    [[noreturn]] void fail_write(const char* step, int err) const { fail("write", shown_, step, err); }
    int check(int ret, const char* step) const {
        if (ret < 0) fail_write(step, ret);
        return ret;
    }

    void end_segment() {
        const int frames = segment_->frames();
        write(segment_->finish());
        segment_.reset();
        first_frame_ += frames;
    }

    // A segment's packets, its times moved to where it starts in the film.
    // x264 starts a segment's decoding times `delay` frames early (its
    // B-frames); a short last segment has fewer B-frames and a smaller
    // delay, so its decoding times move down by the difference to follow
    // the segment before without a gap (a gap made the MP4's average frame
    // rate 305/63 for 5 fps in 60 + 1 frames). Still never after a
    // presentation time.
    void write(const std::vector<Packet>& packets) {
        const std::int64_t delay = packets.empty() ? 0 : std::max<std::int64_t>(0, -packets.front().dts);
        if (first_frame_ == 0) film_delay_ = delay;
        const std::int64_t shift = delay < film_delay_ ? film_delay_ - delay : 0;
        for (const Packet& p : packets) {
            check(av_new_packet(packet_.get(), static_cast<int>(p.data.size())), "writing a packet");
            std::copy(p.data.begin(), p.data.end(), packet_->data);
            packet_->pts = p.pts + first_frame_;
            packet_->dts = p.dts + first_frame_ - shift;
            if (p.key) packet_->flags |= AV_PKT_FLAG_KEY;
            // The muxer picks its own time base (e.g. 1/15360) in write_header.
            av_packet_rescale_ts(packet_.get(), time_base_, stream_->time_base);
            packet_->stream_index = stream_->index;
            check(av_interleaved_write_frame(format_.get(), packet_.get()), "writing a packet");
        }
    }

    SameFreshMemory same_;  // first: on before the stream's encoder opens, off after the muxer is freed
    std::filesystem::path shown_;
    int width_, height_;
    VideoOptions options_;
    std::string codec_name_;
    std::int64_t first_frame_ = 0;  // the film's frames before the current segment
    std::int64_t film_delay_ = 0;   // the first segment's decoding delay, in frames
    AVRational time_base_{1, 1};
    OutputPtr format_;
    AVStream* stream_ = nullptr;  // owned by format_
    std::unique_ptr<FfmpegSegment> segment_;
    PacketPtr packet_;
};

// Yields the decoded frames of a file's best video stream in display order.
class Decoder {
public:
    Decoder(const std::filesystem::path& path, int threads) : path_(path) {
        quiet_ffmpeg();
        const std::string url = file_url(path);
        AVFormatContext* format = nullptr;
        check(avformat_open_input(&format, url.c_str(), nullptr, nullptr), "opening the file");
        format_.reset(format);
        open_stream(threads);
    }

    // The file on `fd` (read from its start, never closed here); `shown` is
    // what errors name. A video stream whose parameters (the container's
    // header, read before any frame is decoded) claim more than
    // `max_pixels` a frame throws ImageTooLarge; libavcodec is held to the
    // same bound (max_pixels) should the stream itself claim more.
    Decoder(int fd, const std::filesystem::path& shown, int threads, std::uint64_t max_pixels = any_pixels)
        : path_(shown), max_pixels_(max_pixels) {
        quiet_ffmpeg();
        AVFormatContext* format = avformat_alloc_context();
        if (!format) check(AVERROR(ENOMEM), "opening the file");
        format->pb = open_file_io(fd, false);
        if (!format->pb) {
            avformat_free_context(format);
            check(AVERROR(ENOMEM), "opening the file");
        }
        format->flags |= AVFMT_FLAG_CUSTOM_IO;
        own_io_.io = format->pb;
        // On failure avformat_open_input frees the context, not our I/O (own_io_ does).
        check(avformat_open_input(&format, nullptr, nullptr, nullptr), "opening the file");
        format_.reset(format);
        open_stream(threads);
    }

    ~Decoder() = default;  // format_, then the I/O it reads through

    Decoder(const Decoder&) = delete;
    Decoder& operator=(const Decoder&) = delete;

    const AVStream* stream() const { return format_->streams[stream_index_]; }
    const std::filesystem::path& path() const { return path_; }

    // The next frame, or nullptr after the last; valid until the next call.
    const AVFrame* next() {
        for (;;) {
            const int ret = avcodec_receive_frame(codec_.get(), frame_.get());
            if (ret == 0) return frame_.get();
            if (ret == AVERROR_EOF) return nullptr;
            if (ret != AVERROR(EAGAIN)) check(ret, "decoding a frame");
            const int read = av_read_frame(format_.get(), packet_.get());
            if (read == AVERROR_EOF) {
                check(avcodec_send_packet(codec_.get(), nullptr), "flushing the decoder");
                continue;
            }
            check(read, "reading a packet");
            const int sent =
                packet_->stream_index == stream_index_ ? avcodec_send_packet(codec_.get(), packet_.get()) : 0;
            av_packet_unref(packet_.get());
            check(sent, "decoding a packet");
        }
    }

    int check(int ret, const char* step) const {
        if (ret < 0) fail("read", path_, step, ret);
        return ret;
    }

private:
    void open_stream(int threads) {
        AVFormatContext* format = format_.get();
        refuse_large_streams();
        // avformat_find_stream_info decodes a few frames with decoders of its
        // own: each gets the same bound.
        std::vector<AVDictionary*> limits(format->nb_streams, nullptr);
        if (max_pixels_ != any_pixels)
            for (AVDictionary*& limit : limits) av_dict_set_int(&limit, "max_pixels", pixel_limit(), 0);
        const int found = avformat_find_stream_info(format, limits.empty() ? nullptr : limits.data());
        for (AVDictionary*& limit : limits) av_dict_free(&limit);
        check(found, "reading the stream info");
        refuse_large_streams();
        const AVCodec* codec = nullptr;
        stream_index_ =
            check(av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0), "finding a video stream");
        codec_.reset(avcodec_alloc_context3(codec));
        frame_.reset(av_frame_alloc());
        packet_.reset(av_packet_alloc());
        if (!codec_ || !frame_ || !packet_) check(AVERROR(ENOMEM), "allocating the decoder");
        check(avcodec_parameters_to_context(codec_.get(), stream()->codecpar), "configuring the decoder");
        codec_->thread_count = threads;
        if (max_pixels_ != any_pixels) codec_->max_pixels = pixel_limit();
        check(avcodec_open2(codec_.get(), codec, nullptr), "opening the decoder");
    }

    // libavcodec's max_pixels is an int64 option.
    std::int64_t pixel_limit() const {
        return static_cast<std::int64_t>(std::min<std::uint64_t>(max_pixels_, INT64_MAX));
    }

    // What the header says of every video stream's frame size, checked
    // before anything is decoded.
    void refuse_large_streams() const {
        for (unsigned i = 0; i < format_->nb_streams; ++i) {
            const AVCodecParameters& p = *format_->streams[i]->codecpar;
            if (p.codec_type != AVMEDIA_TYPE_VIDEO || p.width <= 0 || p.height <= 0) continue;
            const std::uint64_t width = static_cast<std::uint64_t>(p.width),
                                height = static_cast<std::uint64_t>(p.height);
            if (width * height > max_pixels_) throw ImageTooLarge(path_.string(), width, height, max_pixels_);
        }
    }

    std::filesystem::path path_;
    std::uint64_t max_pixels_ = any_pixels;
    // The custom I/O on a descriptor, if any: freed after format_ (declared
    // before it), also when the constructor throws (a stream too large).
    struct OwnIo {
        AVIOContext* io = nullptr;
        OwnIo() = default;
        OwnIo(const OwnIo&) = delete;
        OwnIo& operator=(const OwnIo&) = delete;
        ~OwnIo() { close_file_io(&io); }
    };
    OwnIo own_io_;
    InputPtr format_;
    CodecPtr codec_;
    FramePtr frame_;
    PacketPtr packet_;
    int stream_index_ = -1;
};

std::unique_ptr<Encoder> open_encoder(int fd, const std::filesystem::path& shown, int width, int height,
                                      const VideoOptions& options) {
    return std::make_unique<FfmpegEncoder>(fd, shown, width, height, options);
}

std::unique_ptr<SegmentEncoder> open_segment(const std::filesystem::path& shown, int width, int height,
                                             const VideoOptions& options) {
    return std::make_unique<FfmpegSegment>(shown, width, height, options);
}

VideoInfo probe_video(const std::filesystem::path& path) {
    Decoder decoder(path, 1);  // plenty for tests, and polite under make -j
    VideoInfo info;
    while (const AVFrame* frame = decoder.next()) {
        if (frame->key_frame) info.key_frames.push_back(info.frames);
        ++info.frames;
    }
    const AVStream& s = *decoder.stream();
    const AVCodecParameters& p = *s.codecpar;
    info.width = p.width;
    info.height = p.height;
    const char* pixel_format = av_get_pix_fmt_name(static_cast<AVPixelFormat>(p.format));
    info.pixel_format = pixel_format ? pixel_format : "unknown";
    info.codec = avcodec_get_name(p.codec_id);
    if (s.duration != AV_NOPTS_VALUE) info.duration_seconds = s.duration * av_q2d(s.time_base);
    info.fps = av_q2d(s.avg_frame_rate.num ? s.avg_frame_rate : s.r_frame_rate);
    return info;
}

// A decoded frame as RGBA; errors name `shown`.
Image to_rgba(const AVFrame* frame, const std::filesystem::path& shown) {
    Image image(frame->width, frame->height);
    // FULL_CHR_H_INT: interpolate the chroma for every output pixel.
    ScalerPtr scaler(sws_getContext(frame->width, frame->height, static_cast<AVPixelFormat>(frame->format),
                                    frame->width, frame->height, AV_PIX_FMT_RGBA,
                                    SWS_BICUBIC | SWS_FULL_CHR_H_INT | SWS_ACCURATE_RND | SWS_BITEXACT, nullptr,
                                    nullptr, nullptr));
    if (!scaler) fail("read", shown, "creating the colour converter", AVERROR(EINVAL));
    // Undo the matrix the file says it used (unspecified falls back to BT.601).
    const int* matrix = sws_getCoefficients(frame->colorspace);
    const int full_range = frame->color_range == AVCOL_RANGE_JPEG;
    if (sws_setColorspaceDetails(scaler.get(), matrix, full_range, matrix, 1, 0, 1 << 16, 1 << 16) < 0)
        fail("read", shown, "configuring the colour converter", AVERROR(EINVAL));
    std::uint8_t* const planes[] = {image.rgba.data()};
    const int strides[] = {image.width * 4};
    sws_scale(scaler.get(), frame->data, frame->linesize, 0, frame->height, planes, strides);
    return image;
}

Image to_rgba(const Decoder& decoder, const AVFrame* frame) {
    return to_rgba(frame, decoder.path());
}

Image decode_frame(const std::filesystem::path& path, int index, int threads) {
    Decoder decoder(path, threads);
    const AVFrame* frame = nullptr;
    for (int i = 0; i <= index; ++i) {
        frame = decoder.next();
        if (!frame)
            throw std::out_of_range(path.string() + " has " + std::to_string(i) + " frames, no frame " +
                                    std::to_string(index));
    }
    return to_rgba(decoder, frame);
}

Image decode_film_frame(int fd, const std::filesystem::path& shown, int index, int threads, std::uint64_t max_pixels) {
    Decoder decoder(fd, shown, threads, max_pixels);
    const AVFrame* frame = nullptr;
    for (int i = 0; i <= index; ++i) {
        frame = decoder.next();
        if (!frame)
            throw std::out_of_range(shown.string() + " has " + std::to_string(i) + " frames, no frame " +
                                    std::to_string(index));
    }
    return to_rgba(decoder, frame);
}

Image scale(const Image& image, int width, int height) {
    std::unique_ptr<SwsContext, void (*)(SwsContext*)> scaler(
        sws_getContext(image.width, image.height, AV_PIX_FMT_RGBA, width, height, AV_PIX_FMT_RGBA,
                       SWS_AREA | SWS_ACCURATE_RND, nullptr, nullptr, nullptr),
        sws_freeContext);
    if (!scaler) throw std::runtime_error("thumbnail: libswscale cannot scale RGBA");
    Image out(width, height);
    const std::uint8_t* source[] = {image.rgba.data()};
    const int source_stride[] = {image.width * 4};
    std::uint8_t* target[] = {out.rgba.data()};
    const int target_stride[] = {width * 4};
    if (sws_scale(scaler.get(), source, source_stride, 0, image.height, target, target_stride) != height)
        throw std::runtime_error("thumbnail: libswscale did not fill the image");
    return out;
}

// `frame` scaled to fit max_width x max_height (never enlarged), at least a pixel a side.
Image fitted(const Image& frame, const PreviewOptions& options) {
    const double fit =
        std::min({1.0, double(options.max_width) / frame.width, double(options.max_height) / frame.height});
    const int width = std::max(1, static_cast<int>(std::lround(frame.width * fit)));
    const int height = std::max(1, static_cast<int>(std::lround(frame.height * fit)));
    return width == frame.width && height == frame.height ? frame : scale(frame, width, height);
}

PreviewInfo write_preview(int fd, const std::filesystem::path& shown, int film_fd, int film_frames, int film_fps,
                          const PreviewOptions& options) {
    if (film_frames < 1 || film_fps < 1) throw std::invalid_argument("a preview needs a film of one frame or more");
    const std::vector<int> wanted = preview_frame_indices(film_frames, options);
    std::vector<Image> frames;
    // Decoded on every core (0: as many threads as FFmpeg sees cores): the
    // film just written, waited for; H.264 decodes to the same pixels on
    // any number of threads.
    Decoder decoder(film_fd, shown, 0);
    int index = 0;
    for (std::size_t next = 0; next < wanted.size(); ++index) {
        const AVFrame* frame = decoder.next();
        if (!frame) break;
        if (index != wanted[next]) continue;
        frames.push_back(fitted(to_rgba(decoder, frame), options));
        ++next;
    }
    if (frames.empty()) throw std::runtime_error("cannot write " + shown.string() + ": its film has no frames");
    const double seconds = std::min(options.max_seconds, double(film_frames) / film_fps);
    return write_webp(fd, shown, frames, seconds, options);
}

class WebpPreview final : public PreviewEncoder {
public:
    WebpPreview(const std::filesystem::path& shown, int film_frames, int film_fps, const PreviewOptions& options)
        : shown_(shown),
          options_(options),
          seconds_(std::min(options.max_seconds, double(film_frames) / film_fps)),
          frames_(preview_frame_indices(film_frames, options).size()) {}

    void add(const Image& frame) override {
        if (!encoder_)
            encoder_ = std::make_unique<AnimationEncoder>(shown_, frame.width, frame.height,
                                                          preview_frame_ms(seconds_, frames_), options_.quality);
        encoder_->add(frame);
    }

    PreviewInfo write(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames) override {
        if (frames.empty()) throw std::runtime_error("cannot write " + shown.string() + ": its film has no frames");
        // write_webp's first try, made as the frames came, when they are these.
        std::vector<std::uint8_t> first;
        if (encoder_ && encoder_->frames() == static_cast<int>(frames.size()) && frames.size() == frames_)
            first = encoder_->assemble();
        encoder_.reset();
        return write_webp(fd, shown, frames, seconds_, options_, std::move(first));
    }

private:
    std::filesystem::path shown_;
    PreviewOptions options_;
    double seconds_;
    std::size_t frames_;  // the preview's, before any are dropped for its budget
    std::unique_ptr<AnimationEncoder> encoder_;
};

std::unique_ptr<PreviewEncoder> open_preview(const std::filesystem::path& shown, int film_frames, int film_fps,
                                             const PreviewOptions& options) {
    if (film_frames < 1 || film_fps < 1) throw std::invalid_argument("a preview needs a film of one frame or more");
    return std::make_unique<WebpPreview>(shown, film_frames, film_fps, options);
}

std::uint64_t write_webm(int fd, const std::filesystem::path& shown, int film_fd, int fps, const WebmOptions& webm) {
    Decoder decoder(film_fd, shown, 0);  // every core, the same pixels (see write_preview)
    std::unique_ptr<FfmpegEncoder> encoder;
    VideoOptions options;
    options.fps = fps;
    options.threads = 1;
    options.codec = "libvpx-vp9";
    options.container = "webm";
    options.crf = webm.crf;
    options.speed = webm.speed;
    while (const AVFrame* frame = decoder.next()) {
        const Image rgba = to_rgba(decoder, frame);
        if (!encoder) encoder = std::make_unique<FfmpegEncoder>(fd, shown, rgba.width, rgba.height, options);
        encoder->add(rgba);
    }
    if (!encoder) throw std::runtime_error("cannot write " + shown.string() + ": its film has no frames");
    encoder->finish();
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw std::runtime_error("cannot write " + shown.string() + ": " + std::strerror(errno));
    return static_cast<std::uint64_t>(st.st_size);
}

PreviewInfo write_preview_thumbnail(int fd, const std::filesystem::path& shown, int source_fd,
                                    const std::filesystem::path& source, std::uint64_t max_pixels,
                                    const PreviewOptions& options) {
    // Only the frames kept are held, each scaled as it is decoded: the
    // memory is the decoder's canvas and the small frames, whatever the
    // number of frames.
    int duration_ms = 0;
    const std::vector<Image> frames = decode_webp_frames(
        source_fd, source, max_pixels, options.max_frames, [&](const Image& frame) { return fitted(frame, options); },
        duration_ms);
    return write_webp(fd, shown, frames, duration_ms / 1000.0, options);
}

const Api functions{.open_encoder = open_encoder,
                    .open_segment = open_segment,
                    .probe_video = probe_video,
                    .decode_frame = decode_frame,
                    .scale = scale,
                    .write_preview = write_preview,
                    .probe_preview = probe_webp,
                    .open_preview = open_preview,
                    .write_webm = write_webm,
                    .decode_preview_frame = decode_webp_frame,
                    .write_preview_thumbnail = write_preview_thumbnail,
                    .decode_film_frame = decode_film_frame,
                    .webp_canvas = webp_canvas};

}  // namespace

const Api& implementation() {
    return functions;
}

}  // namespace media::codec
