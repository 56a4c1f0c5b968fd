#pragma once
// FFmpeg's side of figgen (encoding and decoding films, scaling
// thumbnails), built as a module of its own (media/ffmpeg.cpp,
// libfiggen_media.so) that the program opens when it first needs it: loading
// libavcodec, libavformat and libswscale with their dozens of codec
// libraries takes about 55 ms, which a command that writes no film, and
// every --version, list or refused input, does not pay. video.cpp and
// thumbnail.cpp check their arguments and call through this interface; the
// module never touches a path it is not given, and files it writes are the
// descriptors the program opened (AtomicFile).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "render/image.hpp"
#include "media/video.hpp"

namespace media::codec {

using Packet = VideoPacket;

// One segment of a film, encoded on its own: it starts with a key frame and
// refers to no frame outside it, so segments encoded anywhere join by
// stream copy.
class SegmentEncoder {
public:
    virtual ~SegmentEncoder() = default;
    virtual void add(const Image& frame) = 0;  // width x height RGBA, already checked
    virtual std::vector<Packet> finish() = 0;  // flushes; the segment's packets in decoding order
    // After finish(), which frees the encoder: its frames at `indices` (from
    // the segment's start, ascending), decoded back from its `packets` on
    // this thread as a decoder of the whole film gives them, and fitted to
    // the preview's size as write_preview fits them.
    virtual std::vector<Image> preview_frames(const std::vector<Packet>& packets, const std::vector<int>& indices,
                                              const PreviewOptions& options) = 0;
};

// A film's preview (write_preview's animation) encoded as its frames come,
// beside the film rather than after it.
class PreviewEncoder {
public:
    virtual ~PreviewEncoder() = default;
    // The next of the preview's frames (the film's at preview_frame_indices,
    // decoded back and fitted as write_preview fits them), in order.
    virtual void add(const Image& frame) = 0;
    // Writes the preview to `fd`: `frames` are those added, kept for a
    // lower quality should the animation not fit options.max_bytes.
    virtual PreviewInfo write(int fd, const std::filesystem::path& shown, const std::vector<Image>& frames) = 0;
};

// One film being encoded into a file descriptor, segment by segment.
class Encoder {
public:
    virtual ~Encoder() = default;
    // The next frame (width x height RGBA, already checked), encoded in
    // segments of VideoOptions::segment_frames.
    virtual void add(const Image& frame) = 0;
    // The next segment, encoded elsewhere with the same settings, holding `frames` frames.
    virtual void add_segment(const std::vector<Packet>& packets, int frames) = 0;
    virtual void finish() = 0;  // flushes, writes the trailer and closes its I/O
    virtual std::string codec_name() const = 0;
};

// Both sides hold this C++ vocabulary; between them it crosses in plain C
// types (media/media_abi.h): media.cpp turns it into C calls, the module's
// media_abi.cpp turns those back into calls of its implementation().
struct Api {
    // An MP4 writer on `fd` (open for reading and writing; the muxer reads
    // back for faststart); `shown` is the path errors name. Throws
    // std::runtime_error naming `shown` when FFmpeg fails, and
    // std::invalid_argument for an unknown codec.
    std::unique_ptr<Encoder> (*open_encoder)(int fd, const std::filesystem::path& shown, int width, int height,
                                             const VideoOptions& options);
    // A segment encoder; `shown` is what its errors name.
    std::unique_ptr<SegmentEncoder> (*open_segment)(const std::filesystem::path& shown, int width, int height,
                                                    const VideoOptions& options);
    VideoInfo (*probe_video)(const std::filesystem::path& path);
    // Frame `index` (>= 0) decoded with `threads` (>= 0) threads: video.cpp checks both.
    Image (*decode_frame)(const std::filesystem::path& path, int index, int threads);
    // `image` scaled to width x height by area averaging (both at least 1).
    Image (*scale)(const Image& image, int width, int height);
    // The preview of the film of `film_frames` frames at `film_fps` in the
    // MP4 on `film_fd` (read from its start), written to `fd`; `shown` is
    // what errors name.
    PreviewInfo (*write_preview)(int fd, const std::filesystem::path& shown, int film_fd, int film_frames, int film_fps,
                                 const PreviewOptions& options);
    PreviewInfo (*probe_preview)(const std::filesystem::path& path);
    // The preview of a film of `film_frames` frames at `film_fps`, made as
    // its frames come; `shown` is what errors name.
    std::unique_ptr<PreviewEncoder> (*open_preview)(const std::filesystem::path& shown, int film_frames, int film_fps,
                                                    const PreviewOptions& options);
    // The film in the MP4 on `film_fd` (read from its start), `fps` frames
    // a second, encoded again as VP9 in WebM to `fd`; `shown` is what errors
    // name. Returns the WebM's size in bytes.
    std::uint64_t (*write_webm)(int fd, const std::filesystem::path& shown, int film_fd, int fps,
                                const WebmOptions& options);
    Image (*decode_preview_frame)(const std::filesystem::path& path, int index);
    // A smaller copy of the preview on `source_fd` (errors name `source`),
    // on `fd`: its frames (at most options.max_frames of them, evenly
    // spread) scaled to fit options.max_width x max_height, over the same
    // duration. A canvas of more than `max_pixels` is refused from its header
    // (ImageTooLarge).
    PreviewInfo (*write_preview_thumbnail)(int fd, const std::filesystem::path& shown, int source_fd,
                                           const std::filesystem::path& source, std::uint64_t max_pixels,
                                           const PreviewOptions& options);
    // Frame `index` of the film on `fd` (read from its start, never closed
    // here; errors name `shown`), as decode_frame. A video stream whose
    // header claims frames of more than `max_pixels` pixels throws
    // ImageTooLarge before any frame is decoded.
    Image (*decode_film_frame)(int fd, const std::filesystem::path& shown, int index, int threads,
                               std::uint64_t max_pixels);
    // The canvas size of the WebP on `fd`, from its header alone.
    PreviewInfo (*webp_canvas)(int fd, const std::filesystem::path& shown);
};

// The module's functions, opening it on the first call (std::runtime_error
// with one line saying what is missing when it cannot).
const Api& api();

// Starts opening the module on a thread of its own (see render::preload_gl).
void preload();

// The module's own implementation (media/ffmpeg.cpp): defined in the module only.
const Api& implementation();

}  // namespace media::codec
