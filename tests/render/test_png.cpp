#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <sys/resource.h>

#include <csignal>

#include "media/png_io.hpp"

namespace fs = std::filesystem;

namespace {
fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(FIGGEN_TEST_ARTIFACT_DIR) / "png";
    fs::create_directories(dir);
    return dir / name;
}
}  // namespace

TEST_CASE("a PNG written and read back gives the same pixels and text chunks", "[png]") {
    render::Image image(7, 5);  // odd sizes: no row padding assumptions
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(x * 36);
            p[1] = static_cast<std::uint8_t>(y * 60);
            p[2] = static_cast<std::uint8_t>(x * y);
            p[3] = static_cast<std::uint8_t>(255 - x);
        }
    const fs::path path = scratch("round-trip.png");
    const media::TextChunks chunks = {{"Title", "round trip"}, {"figgen:seed", "42"}, {"Caption", "10⁻³ α"}};
    media::write_png(path, image, chunks);
    const media::PngFile back = media::read_png(path);
    CHECK(back.image.width == 7);
    CHECK(back.image.height == 5);
    CHECK(back.image.rgba == image.rgba);
    REQUIRE(back.text.size() == 3);
    CHECK(back.text[2] == std::pair<std::string, std::string>{"Caption", "10⁻³ α"});  // UTF-8 via iTXt
    CHECK(back.text[0] == std::pair<std::string, std::string>{"Title", "round trip"});
    CHECK(back.text[1] == std::pair<std::string, std::string>{"figgen:seed", "42"});
    // Same image, same bytes: no timestamp chunk.
    const fs::path again = scratch("round-trip-2.png");
    media::write_png(again, image, chunks);
    std::ifstream a(path, std::ios::binary), b(again, std::ios::binary);
    CHECK(std::string(std::istreambuf_iterator<char>(a), {}) == std::string(std::istreambuf_iterator<char>(b), {}));
}

TEST_CASE("a PNG written fast holds the same pixels as one written smallest", "[png]") {
    // A smooth gradient with noise, like a field: the two zlib settings give
    // different bytes, and the fast one the larger file.
    render::Image image(320, 200);
    std::uint32_t noise = 12345;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            noise = noise * 1664525u + 1013904223u;
            std::uint8_t* p = image.pixel(x, y);
            p[0] = static_cast<std::uint8_t>(x * 255 / 319);
            p[1] = static_cast<std::uint8_t>(y * 255 / 199);
            p[2] = static_cast<std::uint8_t>(noise >> 28);
            p[3] = 255;
        }
    const fs::path dir = scratch("fast").parent_path();
    const base::Folder folder(dir);
    media::write_png(folder, "smallest.png", image);
    media::write_png(folder, "fast.png", image, {}, base::AtomicFile::Commit::now, media::PngCompression::fast);
    CHECK(media::read_png(dir / "fast.png").image.rgba == image.rgba);
    CHECK(media::read_png(dir / "smallest.png").image.rgba == image.rgba);
    CHECK(fs::file_size(dir / "fast.png") > fs::file_size(dir / "smallest.png"));
}

TEST_CASE("a PNG that cannot be written leaves nothing behind", "[png]") {
    render::Image image(4, 4);
    const fs::path inside_a_file = scratch("not-a-folder.txt");
    std::ofstream(inside_a_file) << "x";
    const fs::path target = inside_a_file / "image.png";
    CHECK_THROWS_WITH(media::write_png(target, image), Catch::Contains(target.string()));

}

TEST_CASE("reading a file that is not a PNG fails with its name", "[png]") {
    const fs::path bogus = scratch("bogus.png");
    std::ofstream(bogus) << "definitely not a PNG";
    CHECK_THROWS_WITH(media::read_png(bogus), Catch::Contains("bogus.png"));
    CHECK_THROWS_WITH(media::read_png(scratch("missing.png")), Catch::Contains("missing.png"));
}

TEST_CASE("a disk that fills up mid-write leaves no PNG, whole or partial", "[png]") {
    // A file-size limit fails writes past it with EFBIG, the way a full disk
    // fails them with ENOSPC; SIGXFSZ is ignored so the write returns an error.
    render::Image noise(256, 256);
    std::uint32_t x = 12345;
    for (auto& byte : noise.rgba) byte = static_cast<std::uint8_t>((x = x * 1103515245u + 12345u) >> 24);
    const fs::path target = scratch("full-disk.png");
    fs::remove(target);
    rlimit saved{};
    getrlimit(RLIMIT_FSIZE, &saved);
    const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
    rlimit small = saved;
    small.rlim_cur = 4096;
    setrlimit(RLIMIT_FSIZE, &small);
    std::string message;
    try {
        media::write_png(target, noise);
    } catch (const std::runtime_error& e) {
        message = e.what();
    }
    setrlimit(RLIMIT_FSIZE, &saved);
    std::signal(SIGXFSZ, old_handler);
    CHECK_THAT(message, Catch::Contains("cannot write") && Catch::Contains("full-disk.png"));
    CHECK_FALSE(fs::exists(target));
    for (const auto& entry : fs::directory_iterator(target.parent_path()))
        CHECK(entry.path().filename().string().find("full-disk.png.tmp") == std::string::npos);
}

TEST_CASE("an opaque image is stored as RGB and one with any transparency as RGBA", "[png]") {
    // The colour type is byte 25 of the file (IHDR's tenth data byte): 2 is
    // RGB, 6 RGBA. Both read back as the RGBA they were written from.
    render::Image image(9, 4);
    for (std::size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<std::uint8_t>(i % 4 == 3 ? 255 : i);
    auto colour_type = [](const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes(std::istreambuf_iterator<char>(in), {});
        REQUIRE(bytes.size() > 25);
        return static_cast<int>(static_cast<unsigned char>(bytes[25]));
    };
    const fs::path opaque = scratch("opaque.png");
    media::write_png(opaque, image);
    CHECK(colour_type(opaque) == 2);
    CHECK(media::read_png(opaque).image.rgba == image.rgba);

    image.pixel(8, 3)[3] = 254;
    const fs::path translucent = scratch("translucent.png");
    media::write_png(translucent, image);
    CHECK(colour_type(translucent) == 6);
    CHECK(media::read_png(translucent).image.rgba == image.rgba);
}
