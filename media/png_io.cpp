#include "media/png_io.hpp"

#include <fcntl.h>
#include <png.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

#include "base/atomic_file.hpp"

namespace media {
namespace {

struct FileCloser {
    void operator()(std::FILE* f) const {
        if (f) std::fclose(f);
    }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

// libpng reports errors through a callback; we keep its message and longjmp
// back to the setjmp in the caller, which turns it into an exception.
struct ErrorState {
    std::jmp_buf jump;
    char message[256] = "";
};

[[noreturn]] void on_error(png_structp png, png_const_charp message) {
    auto* state = static_cast<ErrorState*>(png_get_error_ptr(png));
    std::snprintf(state->message, sizeof state->message, "%s", message);
    std::longjmp(state->jump, 1);
}

void on_warning(png_structp, png_const_charp) {}

// How the rows are filtered and compressed: an opaque image is stored as RGB
// (a quarter fewer bytes to filter and compress; read back as RGBA with
// alpha 255), and the filters are picked per image (see choose_filters).
struct Settings {
    bool opaque = false;
    int level = 4;
    int filters = PNG_ALL_FILTERS;
};

// Where encode() writes: a FILE, or nowhere, counting the bytes, for
// choose_filters' trials (which need only the size).
struct Sink {
    std::FILE* file = nullptr;
    std::size_t* counted = nullptr;
};

void count_bytes(png_structp png, png_bytep, png_size_t length) {
    *static_cast<std::size_t*>(png_get_io_ptr(png)) += length;
}

void flush_nothing(png_structp) {}

// Encodes `height` rows of `width` RGBA pixels into `sink`. Kept free of
// C++ objects with destructors, as code between setjmp and longjmp must be;
// returns false with state.message set.
bool encode(Sink sink, png_bytep* rows, int width, int height, png_text* records, int record_count,
            const Settings& settings, ErrorState& state) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        std::snprintf(state.message, sizeof state.message, "out of memory");
        return false;
    }
    if (setjmp(state.jump)) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    if (sink.file)
        png_init_io(png, sink.file);
    else
        png_set_write_fn(png, sink.counted, count_bytes, flush_nothing);
    png_set_IHDR(png, info, width, height, 8, settings.opaque ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_RGBA,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, settings.level);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, settings.filters);
    if (record_count > 0) png_set_text(png, info, records, record_count);
    png_write_info(png, info);
    if (settings.opaque) png_set_filler(png, 0, PNG_FILLER_AFTER);  // the rows hold RGBA; the file gets RGB
    png_write_image(png, rows);
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    return true;
}

// libpng's adaptive filters (it picks, row by row, the filter whose output
// has the smallest sum of magnitudes) suit smooth fields, but on flat
// colours (plots, cells, lines on white) no filter compresses far better:
// gs-atlas's PNG is 650 KB unfiltered against 998 KB. So each figure tries
// both on a sample, 8 rows in every 128, and keeps the smaller. Over the 29
// catalog figures (measured with a scratch encoder on make figures' PNGs,
// level 4 both ways) this writes 2.57 MB in 0.37 s, where the adaptive
// filters at zlib's default level wrote 3.47 MB in 0.90 s; tc7-2's smooth
// field keeps its filters. The trials only count their bytes.
int choose_filters(png_bytep* rows, int width, int height, const Settings& settings) {
    constexpr int band = 8, every = 128;
    std::vector<png_bytep> sample;
    for (int y0 = 0; y0 < height; y0 += every)
        for (int y = y0; y < std::min(y0 + band, height); ++y) sample.push_back(rows[y]);
    std::size_t best = 0;
    int choice = PNG_ALL_FILTERS;
    for (int filters : {PNG_ALL_FILTERS, PNG_FILTER_NONE}) {
        Settings trial = settings;
        trial.filters = filters;
        std::size_t bytes = 0;
        ErrorState state;
        if (!encode(Sink{nullptr, &bytes}, sample.data(), width, static_cast<int>(sample.size()), nullptr, 0, trial,
                    state))
            return PNG_ALL_FILTERS;  // the real encode will say what is wrong
        if (best == 0 || bytes < best) {
            best = bytes;
            choice = filters;
        }
    }
    return choice;
}

// What the header of a PNG refused for its size claims.
struct Claimed {
    std::uint64_t width = 0, height = 0;
};

// Decodes `in` into `result` (8-bit RGBA whatever the stored format), or
// stops after the header when it claims more than `max_pixels` (returns
// false with `too_large` filled in). Like encode(), free of objects with
// destructors between setjmp and longjmp.
bool decode(std::FILE* in, PngFile& result, ErrorState& state, std::uint64_t max_pixels, Claimed& too_large) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, on_error, on_warning);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        std::snprintf(state.message, sizeof state.message, "out of memory");
        return false;
    }
    if (setjmp(state.jump)) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_init_io(png, in);
    png_read_info(png, info);
    const std::uint64_t claimed_width = png_get_image_width(png, info),
                        claimed_height = png_get_image_height(png, info);
    if (claimed_width * claimed_height > max_pixels) {  // both below 2^31 (libpng checks): no overflow
        too_large = {claimed_width, claimed_height};
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_set_expand(png);
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    const int width = static_cast<int>(png_get_image_width(png, info));
    const int height = static_cast<int>(png_get_image_height(png, info));
    result.image = Image(width, height);
    for (int pass = 0; pass < passes; ++pass)
        for (int y = 0; y < height; ++y) png_read_row(png, result.image.pixel(0, y), nullptr);
    png_read_end(png, info);
    png_textp records = nullptr;
    const int count = png_get_text(png, info, &records, nullptr);
    for (int i = 0; i < count; ++i) result.text.emplace_back(records[i].key, records[i].text);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

}  // namespace

void write_png(const base::Folder& folder, const std::string& name, const Image& image, const TextChunks& text,
               base::AtomicFile::Commit when, PngCompression compression) {
    if (image.width < 1 || image.height < 1 ||
        image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
        throw std::invalid_argument("write_png: image is empty or its pixel buffer has the wrong size");
    base::AtomicFile file(folder, name, when);
    const std::filesystem::path path = file.final_path();
    File out(file.take_stream());

    std::vector<png_bytep> rows(image.height);
    for (int y = 0; y < image.height; ++y)
        rows[y] = const_cast<png_bytep>(image.rgba.data() + static_cast<std::size_t>(y) * image.width * 4);
    std::vector<png_text> records(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        // tEXt holds Latin-1 only; anything beyond ASCII goes in an iTXt
        // chunk, which is UTF-8, as our strings are.
        const bool ascii = std::all_of(text[i].second.begin(), text[i].second.end(),
                                       [](char c) { return static_cast<unsigned char>(c) < 0x80; });
        records[i].compression = ascii ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
        records[i].key = const_cast<char*>(text[i].first.c_str());
        records[i].text = const_cast<char*>(text[i].second.c_str());
    }
    Settings settings;
    settings.opaque = std::all_of(rows.begin(), rows.end(), [&](png_bytep row) {
        for (int x = 0; x < image.width; ++x)
            if (row[4 * x + 3] != 255) return false;
        return true;
    });
    if (compression == PngCompression::fast) {
        settings.level = 1;
        settings.filters = PNG_FILTER_SUB;
    } else {
        settings.filters = choose_filters(rows.data(), image.width, image.height, settings);
    }
    ErrorState state;
    errno = 0;
    if (!encode(Sink{out.get(), nullptr}, rows.data(), image.width, image.height, records.data(),
                static_cast<int>(records.size()), settings, state)) {
        // libpng says only "Write Error" when fwrite fails; the system says why.
        const bool system = std::ferror(out.get()) && errno != 0;
        throw std::runtime_error("cannot write " + path.string() + ": " +
                                 (system ? std::string(std::strerror(errno)) : state.message));
    }

    // A full disk often shows only when the buffered bytes are flushed.
    if (std::fflush(out.get()) != 0 || std::ferror(out.get()))
        throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
    if (std::fclose(out.release()) != 0)
        throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
    file.commit();
}

void write_png(const std::filesystem::path& path, const Image& image, const TextChunks& text) {
    write_png(base::Folder::of(path), path.filename().string(), image, text);
}

namespace {

PngFile read_png_from(std::FILE* stream, const std::filesystem::path& path, std::uint64_t max_pixels = any_pixels) {
    File in(stream);
    PngFile result;
    ErrorState state;
    Claimed claimed;
    if (!decode(in.get(), result, state, max_pixels, claimed)) {
        if (claimed.width > 0) throw ImageTooLarge(path.string(), claimed.width, claimed.height, max_pixels);
        throw std::runtime_error("cannot read " + path.string() + ": " + state.message);
    }
    return result;
}

}  // namespace

PngFile read_png(const base::Folder& folder, const std::string& name, std::uint64_t max_pixels) {
    const int fd = base::open_regular_at(folder, name);
    if (fd < 0)
        throw std::runtime_error("cannot read " + (folder / name).string() + ": " + base::not_opened_reason(errno));
    std::FILE* stream = ::fdopen(fd, "rb");
    if (!stream) {
        ::close(fd);
        throw std::runtime_error("cannot read " + (folder / name).string() + ": " + std::strerror(errno));
    }
    return read_png_from(stream, folder / name, max_pixels);
}

PngFile read_png(const std::filesystem::path& path) {
    std::FILE* in = std::fopen(path.c_str(), "rb");
    if (!in) throw std::runtime_error("cannot read " + path.string() + ": " + std::strerror(errno));
    return read_png_from(in, path);
}

}  // namespace media
