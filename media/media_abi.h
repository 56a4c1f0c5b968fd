/* The media module's interface (libfiggen_media.so: FFmpeg and libwebp) in
 * plain C types: numbers, NUL-terminated strings, pointers to arrays the
 * caller owns, opaque handles for the encoders, callbacks through which the
 * module hands back images and packets (written straight into the
 * program's own buffers), and an error record in place of an exception.
 * media/media_abi.cpp is the module's side, media/media.cpp the
 * program's; both keep media/media.hpp's C++ vocabulary on their side. */
#ifndef FIGGEN_MEDIA_ABI_H
#define FIGGEN_MEDIA_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever anything below changes: a module of another build is refused. */
enum { FIGGEN_MEDIA_ABI_VERSION = 8 };

/* What failed: the exception the program throws again. */
enum figgen_media_error_kind {
    FIGGEN_MEDIA_OK = 0,
    FIGGEN_MEDIA_RUNTIME_ERROR = 1,   /* FFmpeg or libwebp failed, a file cannot be read or written */
    FIGGEN_MEDIA_INVALID_ARGUMENT = 2,
    FIGGEN_MEDIA_LOGIC_ERROR = 3,
    FIGGEN_MEDIA_IMAGE_TOO_LARGE = 4, /* a header claims more pixels than allowed */
    FIGGEN_MEDIA_OUT_OF_RANGE = 5     /* no such frame */
};
typedef struct figgen_media_error {
    int32_t kind;
    char message[4096];                   /* one line */
    char file[4096];                      /* IMAGE_TOO_LARGE: the file */
    uint64_t width, height, max_pixels;   /* IMAGE_TOO_LARGE: what the header claims, what was allowed */
} figgen_media_error;

/* An image the caller owns: width x height RGBA, rows top down. */
typedef struct figgen_media_image {
    int32_t width, height;
    const uint8_t* rgba;
} figgen_media_image;
/* Where the module puts an image it makes: `pixels` returns a buffer of
 * width * height * 4 bytes for it (null: stop), which the module fills. */
typedef struct figgen_media_image_sink {
    void* context;
    uint8_t* (*pixels)(void* context, int32_t width, int32_t height);
} figgen_media_image_sink;

typedef struct figgen_media_packet {
    const uint8_t* data;
    size_t size;
    int64_t pts, dts;
    int32_t key;
} figgen_media_packet;
typedef struct figgen_media_packet_sink {
    void* context;
    void (*packet)(void* context, const figgen_media_packet* packet);
} figgen_media_packet_sink;

typedef struct figgen_video_options {
    int32_t fps, threads, crf;
    const char* codec;     /* "auto", "libx264" or "mpeg4" */
    const char* preset;
    const char* tune;
    int32_t segment_frames;
    const char* container; /* "mp4" or "webm" */
    int32_t speed;
} figgen_video_options;

typedef struct figgen_preview_options {
    int32_t max_width, max_height, max_frames;
    double max_seconds;
    float quality;
    uint64_t max_bytes;
} figgen_preview_options;

typedef struct figgen_webm_options {
    int32_t crf, speed;
} figgen_webm_options;

typedef struct figgen_preview_info {
    int32_t frames, width, height, loop_count, duration_ms;
    uint64_t bytes;
    float quality;
} figgen_preview_info;

/* A video's description; the texts and the key frames stay valid until the
 * next call on the same thread. */
typedef struct figgen_video_info {
    int32_t frames, width, height;
    const char* pixel_format;
    const char* codec;
    double duration_seconds, fps;
    const int32_t* key_frames;
    size_t key_frame_count;
} figgen_video_info;

typedef struct figgen_media_encoder figgen_media_encoder;   /* a film encoded into a descriptor */
typedef struct figgen_media_segment figgen_media_segment;   /* one segment of a film, encoded on its own */
typedef struct figgen_media_preview figgen_media_preview;   /* a film's preview, made as its frames come */

/* Every function returns 0, or nonzero after filling *error. `shown` is the
 * path errors name; the descriptors are the caller's, never closed here.
 * The meaning of each is media/media.hpp's Api. */
typedef struct figgen_media_api {
    int32_t version; /* FIGGEN_MEDIA_ABI_VERSION */

    int (*open_encoder)(int fd, const char* shown, int32_t width, int32_t height, const figgen_video_options* options,
                        figgen_media_encoder** out, figgen_media_error* error);
    int (*encoder_add)(figgen_media_encoder* encoder, const figgen_media_image* frame, figgen_media_error* error);
    int (*encoder_add_segment)(figgen_media_encoder* encoder, const figgen_media_packet* packets, size_t count,
                               int32_t frames, figgen_media_error* error);
    int (*encoder_finish)(figgen_media_encoder* encoder, figgen_media_error* error);
    const char* (*encoder_codec)(const figgen_media_encoder* encoder);
    void (*encoder_close)(figgen_media_encoder* encoder);

    int (*open_segment)(const char* shown, int32_t width, int32_t height, const figgen_video_options* options,
                        figgen_media_segment** out, figgen_media_error* error);
    int (*segment_add)(figgen_media_segment* segment, const figgen_media_image* frame, figgen_media_error* error);
    int (*segment_finish)(figgen_media_segment* segment, figgen_media_packet_sink sink, figgen_media_error* error);
    int (*segment_preview_frames)(figgen_media_segment* segment, const figgen_media_packet* packets, size_t count,
                                  const int32_t* indices, size_t index_count, const figgen_preview_options* options,
                                  figgen_media_image_sink sink, figgen_media_error* error);
    void (*segment_close)(figgen_media_segment* segment);

    int (*open_preview)(const char* shown, int32_t film_frames, int32_t film_fps,
                        const figgen_preview_options* options, figgen_media_preview** out, figgen_media_error* error);
    int (*preview_add)(figgen_media_preview* preview, const figgen_media_image* frame, figgen_media_error* error);
    int (*preview_write)(figgen_media_preview* preview, int fd, const char* shown, const figgen_media_image* frames,
                         size_t count, figgen_preview_info* info, figgen_media_error* error);
    void (*preview_close)(figgen_media_preview* preview);

    int (*probe_video)(const char* path, figgen_video_info* info, figgen_media_error* error);
    int (*decode_frame)(const char* path, int32_t index, int32_t threads, figgen_media_image_sink sink,
                        figgen_media_error* error);
    int (*scale)(const figgen_media_image* image, int32_t width, int32_t height, figgen_media_image_sink sink,
                 figgen_media_error* error);
    int (*write_preview)(int fd, const char* shown, int film_fd, int32_t film_frames, int32_t film_fps,
                         const figgen_preview_options* options, figgen_preview_info* info, figgen_media_error* error);
    int (*probe_preview)(const char* path, figgen_preview_info* info, figgen_media_error* error);
    int (*write_webm)(int fd, const char* shown, int film_fd, int32_t fps, const figgen_webm_options* options,
                      uint64_t* bytes, figgen_media_error* error);
    int (*decode_preview_frame)(const char* path, int32_t index, figgen_media_image_sink sink,
                                figgen_media_error* error);
    int (*write_preview_thumbnail)(int fd, const char* shown, int source_fd, const char* source, uint64_t max_pixels,
                                   const figgen_preview_options* options, figgen_preview_info* info,
                                   figgen_media_error* error);
    int (*decode_film_frame)(int fd, const char* shown, int32_t index, int32_t threads, uint64_t max_pixels,
                             figgen_media_image_sink sink, figgen_media_error* error);
    int (*webp_canvas)(int fd, const char* shown, figgen_preview_info* info, figgen_media_error* error);
} figgen_media_api;

/* The module's one entry point. */
const figgen_media_api* figgen_media_module(void);

#ifdef __cplusplus
}
#endif

#endif
