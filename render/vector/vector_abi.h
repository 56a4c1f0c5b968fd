/* The vector module's interface (libfiggen_vector.so, render/vector/cairo.cpp)
 * in plain C types: what crosses the dlopen boundary is numbers, pointers to
 * arrays the program owns, and NUL-terminated strings; no exception, no
 * library type of either side. The program (render/vector/vector.cpp) hands
 * the module its page one item at a time (figgen_vector_page.item), so that
 * no second copy of a large page is ever made. */
#ifndef FIGGEN_VECTOR_ABI_H
#define FIGGEN_VECTOR_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Bumped whenever anything below changes: a module of another build is refused. */
enum { FIGGEN_VECTOR_ABI_VERSION = 3 };

enum figgen_vector_format { FIGGEN_VECTOR_PDF = 0, FIGGEN_VECTOR_SVG = 1 };

/* One piece of a path, in pixels of the page (top-left origin, y down). */
enum figgen_path_kind {
    FIGGEN_PATH_MOVE = 0,   /* starts a subpath at (x, y) */
    FIGGEN_PATH_LINE = 1,   /* a straight line to (x, y) */
    FIGGEN_PATH_CLOSE = 2,  /* back to the subpath's start */
    FIGGEN_PATH_CIRCLE = 3  /* a whole circle about (x, y) of `radius`, counter-clockwise on screen, a subpath of its own */
};
typedef struct figgen_path_step {
    int32_t kind;
    float x, y;
    float radius;
} figgen_path_step;

typedef struct figgen_glyph {
    uint32_t index; /* in the item's face */
    float x, y;     /* from the line's origin in the line's frame, pixels, y down */
} figgen_glyph;

/* cairo's text clusters: `bytes` of the text drawn by `glyphs` glyphs. */
typedef struct figgen_cluster {
    int32_t bytes, glyphs;
} figgen_cluster;

enum figgen_item_kind {
    FIGGEN_ITEM_FILL = 0,
    FIGGEN_ITEM_STROKE = 1,
    FIGGEN_ITEM_GLYPHS = 2,
    FIGGEN_ITEM_PICTURE = 3,
    FIGGEN_ITEM_CLIP = 4,        /* until the next UNCLIP */
    FIGGEN_ITEM_UNCLIP = 5,
    FIGGEN_ITEM_GROUP_BEGIN = 6, /* what follows is drawn opaque, then laid over the page at the END's alpha */
    FIGGEN_ITEM_GROUP_END = 7
};
enum figgen_cap { FIGGEN_CAP_BUTT = 0, FIGGEN_CAP_SQUARE = 1, FIGGEN_CAP_ROUND = 2 };

/* One item of the page; the fields its kind uses are set, the rest zero.
 * Colours are RGBA from 0 to 1, straight alpha. */
typedef struct figgen_vector_item {
    int32_t kind;
    float colour[4];                 /* FILL, STROKE, GLYPHS */
    const figgen_path_step* path;    /* FILL, STROKE */
    size_t path_steps;
    int32_t even_odd;                /* FILL: the even-odd rule (else nonzero) */
    float width;                     /* STROKE: pixels; round caps also join round, others mitre to 2, then round */
    int32_t cap;                     /* STROKE */
    const float* dash;               /* STROKE: on, off, ... pixels (an even count); none: solid */
    size_t dash_count;
    float dash_offset;
    const char* font_path;           /* GLYPHS: the font file the glyph indices are of */
    int32_t font_index;              /* the face within it */
    float pixel_size;                /* em size, pixels */
    float origin[2];                 /* the line's start on the baseline */
    float rotation_degrees;          /* counter-clockwise on screen about the origin */
    const figgen_glyph* glyphs;      /* left to right on the page */
    size_t glyph_count;
    const char* text;                /* the characters drawn, UTF-8 (not NUL-terminated), for search and copying */
    size_t text_bytes;
    const figgen_cluster* clusters;  /* in the text's order */
    size_t cluster_count;
    int32_t backward;                /* the glyphs run right to left through the text */
    const uint8_t* pixels;           /* PICTURE: RGBA rows top down, straight alpha */
    int32_t image_width, image_height;
    float box[4];                    /* PICTURE: the rectangle it fills (x, y, w, h); CLIP: x0, y0, x1, y1 */
    int32_t smooth;                  /* PICTURE: 0: nearest sampling, so that a viewer never blurs the cells */
    float alpha;                     /* GROUP_END */
} figgen_vector_item;

typedef struct figgen_vector_page {
    int32_t width, height; /* pixels: a PDF page is 0.72 pt a pixel (the PNG at 100 dpi), an SVG's a CSS px */
    const char* title;     /* the document's title */
    const char* creator;   /* "figgen 1.2.3" */
    size_t item_count;     /* painted in order */
    /* Fills *item with item `index` (< item_count) of `items`; what it
     * points to stays valid until the next call. Returns 0. */
    int (*item)(void* items, size_t index, figgen_vector_item* item);
    void* items;
} figgen_vector_page;

typedef struct figgen_vector_api {
    int32_t version; /* FIGGEN_VECTOR_ABI_VERSION */
    /* Writes `page` as `format` to `fd` (open for writing, at its start),
     * never more than `max_bytes`. Returns 0, or nonzero after writing a
     * one-line message naming `shown` (the path errors show) into
     * error[error_size] (cairo failed, a full disk, a font that cannot
     * load, the file would pass max_bytes). */
    int (*write)(int fd, const char* shown, int32_t format, const figgen_vector_page* page, uint64_t max_bytes,
                 char* error, size_t error_size);
} figgen_vector_api;

/* The module's one entry point. */
const figgen_vector_api* figgen_vector_module(void);

#ifdef __cplusplus
}
#endif

#endif
