// The output formats' table (app/render/formats.hpp): --format's names choose the
// formats they name, each file has a name of its own, and the disk and
// memory estimates are the table's entries added up.
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "app/render/estimates.hpp"
#include "app/render/formats.hpp"
#include "app/render/output_files.hpp"
#include "description/catalog.hpp"
#include "description/description.hpp"

namespace {

description::Description catalog(const std::string& id) {
    return description::load_description(description::resolve_figure(id));
}

}  // namespace

TEST_CASE("each --format name chooses its own format and no other", "[formats]") {
    const description::Description film = catalog("tc7-2");  // a figure with a film
    REQUIRE(film.animation);
    const std::vector<std::string> names = app::format_names();
    REQUIRE(names.size() >= 2);
    for (const std::string& name : names) {
        INFO(name);
        const app::OutputFormat* chosen = app::output_format(name);
        REQUIRE(chosen);
        app::OutputOptions options;
        options.video = false;  // as --format leaves it until mp4 is named
        options.formats_given = true;
        chosen->choose(options);
        CHECK(chosen->wanted(film, options));
        for (const std::string& other : names) {
            const app::OutputFormat* f = app::output_format(other);
            // png is always written; the rest only when named, but the
            // WebM is made from an MP4 (on disk while it is, so counted).
            if (other == name || other == "png" || (name == "webm" && other == "mp4")) continue;
            CHECK_FALSE(f->wanted(film, options));
        }
    }
    CHECK(app::output_format("gif") == nullptr);
}

TEST_CASE("every format's file has a name of its own, and a temporary of each is swept", "[formats]") {
    const std::vector<std::string> names = app::output_names("tc7-2");
    CHECK(names.size() == app::output_formats().size());
    CHECK(std::set<std::string>(names.begin(), names.end()).size() == names.size());
    for (const app::OutputFormat& f : app::output_formats()) CHECK(std::string(f.suffix).size() >= 4);
}

TEST_CASE("the disk estimate is each chosen file's bound added up", "[formats]") {
    const description::Description still = catalog("tc7-7");  // 900 x 450, no film
    REQUIRE_FALSE(still.animation);
    app::OutputOptions options;
    options.formats_given = true;
    options.video = false;
    const double png = 4.0 * 900 * 450, vector = 16.0 * 900 * 450 + 1024 * 1024;
    // Just under and just over the PNG with the PDF and the SVG.
    app::output_format("pdf")->choose(options);
    app::output_format("svg")->choose(options);
    options.max_disk = static_cast<std::uint64_t>(png + 2 * vector) + 1;
    CHECK_NOTHROW(app::require_disk(still, options));
    options.max_disk = static_cast<std::uint64_t>(png + 2 * vector) - 1;
    CHECK_THROWS_WITH(app::require_disk(still, options), Catch::Contains("(mostly the PDF)"));
    // The vector page is counted once for both vector files.
    const app::MemoryEstimate with_both = app::estimate_memory(still, options, {});
    app::OutputOptions pdf_only;
    pdf_only.formats_given = true;
    pdf_only.video = false;
    app::output_format("pdf")->choose(pdf_only);
    CHECK(app::estimate_memory(still, pdf_only, {}).bytes == with_both.bytes);
    app::OutputOptions png_only;
    png_only.formats_given = true;
    png_only.video = false;
    CHECK(with_both.bytes - app::estimate_memory(still, png_only, {}).bytes ==
          Approx(render::vector::page_bytes + render::vector::page_bytes_per_pixel * 900 * 450));
}
