#include "image_check.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "base/digest.hpp"
#include "media/png_io.hpp"

namespace testkit {
namespace {

const std::filesystem::path golden_dir = FIGGEN_TEST_GOLDEN_DIR;
const std::filesystem::path artifact_dir = FIGGEN_TEST_ARTIFACT_DIR;

// Differences magnified so a reviewer sees them: black where equal, red where
// a channel is off by more than max_delta, grey for smaller deltas.
render::Image diff_image(const render::Image& a, const render::Image& b) {
    render::Image diff(a.width, a.height);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            int delta = 0;
            for (int c = 0; c < 4; ++c) delta = std::max(delta, std::abs(a.pixel(x, y)[c] - b.pixel(x, y)[c]));
            std::uint8_t* out = diff.pixel(x, y);
            const auto grey = static_cast<std::uint8_t>(std::min(255, delta * 40));
            out[0] = delta > max_delta ? 255 : grey;
            out[1] = delta > max_delta ? 0 : grey;
            out[2] = delta > max_delta ? 0 : grey;
            out[3] = 255;
        }
    return diff;
}

}  // namespace

std::string pixel_hash(const render::Image& image) {
    return base::sha256_hex(image.rgba.data(), image.rgba.size());
}

GoldenCheck check_golden(const std::string& name, const render::Image& actual, const std::string& renderer) {
    GoldenCheck result;
    std::string expected_hash, recorded_renderer, recorded_version;
    {
        std::ifstream in(golden_dir / (name + ".sha256"));
        std::getline(in, expected_hash);
        std::getline(in, recorded_renderer);
        std::getline(in, recorded_version);
    }
    result.recorded_renderer = recorded_renderer + "\n" + recorded_version;
    const std::string hash = pixel_hash(actual);
    if (!expected_hash.empty() && hash == expected_hash) {
        result.hash_matched = result.within_tolerance = true;
        result.message = name + ": pixel hash matches";
        return result;
    }
    const auto golden_png = golden_dir / (name + ".png");
    if (!std::filesystem::exists(golden_png)) {
        result.message = name + ": no golden " + golden_png.string() + " (run `make goldens`)";
        return result;
    }
    const render::Image golden = media::read_png(golden_png).image;
    std::filesystem::create_directories(artifact_dir);
    media::write_png(artifact_dir / (name + "-actual.png"), actual);
    if (golden.width != actual.width || golden.height != actual.height) {
        std::ostringstream m;
        m << name << ": size " << actual.width << "x" << actual.height << " differs from the golden's "
          << golden.width << "x" << golden.height;
        result.message = m.str();
        return result;
    }
    for (int y = 0; y < golden.height; ++y)
        for (int x = 0; x < golden.width; ++x) {
            int delta = 0;
            for (int c = 0; c < 4; ++c)
                delta = std::max(delta, std::abs(golden.pixel(x, y)[c] - actual.pixel(x, y)[c]));
            result.largest_delta = std::max(result.largest_delta, delta);
            if (delta > max_delta) ++result.differing_pixels;
        }
    const long allowed = static_cast<long>(max_differing_fraction * golden.width * golden.height);
    result.within_tolerance = result.differing_pixels <= allowed;
    media::write_png(artifact_dir / (name + "-diff.png"), diff_image(golden, actual));
    std::ostringstream m;
    m << name << ": hash differs (golden made with " << recorded_renderer << ", this is "
      << renderer << "); " << result.differing_pixels << " pixels differ by more than "
      << max_delta << " (allowed " << allowed << "), largest delta " << result.largest_delta << "; see "
      << (artifact_dir / (name + "-diff.png")).string();
    result.message = m.str();
    return result;
}

void write_golden(const std::filesystem::path& dir, const std::string& name, const render::Image& image,
                  const std::string& renderer, const std::string& version) {
    std::filesystem::create_directories(dir);
    media::write_png(dir / (name + ".png"), image);
    std::ofstream out(dir / (name + ".sha256"));
    out << pixel_hash(image) << "\n" << renderer << "\n" << version << "\n";
    if (!out) throw std::runtime_error("cannot write " + (dir / (name + ".sha256")).string());
}

}  // namespace testkit
