#pragma once
// Checks of a figure's PDF and SVG against its PNG, with the tools a reader
// of them would use: poppler's pdffonts and pdftoppm, librsvg's rsvg-convert.
//
// A vector file rasterised by another library never matches GL's pixels
// exactly (its antialiasing, its font rasteriser, how it samples an image
// with more cells than pixels), so the comparison is of local means: both
// images over white, cut into blocks of vector_block x vector_block pixels,
// and per block the largest channel difference of the blocks' means (0..255).
// The stated tolerance: a mean over blocks of at most vector_mean_tolerance
// and a 99th percentile of at most vector_p99_tolerance. Measured on the
// catalog at half size: means 0.4..5.3 and 99th percentiles up to 35 (PDF:
// pdftoppm's fonts and its sampling of dense fields; bd-500 and tc7-ex2 have
// more cells than pixels); a panel drawn in the wrong place or colour, or a
// missing plot, moves them by tens.

#include <filesystem>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace testkit {

inline constexpr int vector_block = 8;
inline constexpr double vector_mean_tolerance = 6;
inline constexpr double vector_p99_tolerance = 40;

struct BlockDifference {
    bool comparable = false;  // the same size, or one row or column more (a page's points rounded up)
    double mean = 0, p99 = 0, max = 0;
    std::string message;      // one line for the test log
    bool within_tolerance() const {
        return comparable && mean <= vector_mean_tolerance && p99 <= vector_p99_tolerance;
    }
};
BlockDifference block_difference(const render::Image& expected, const render::Image& actual,
                                 int block = vector_block);

// A shell command's exit status and its output (stdout and stderr).
struct ToolRun {
    int status = -1;
    std::string output;
};
ToolRun run_tool(const std::string& command);

// pdffonts' table of `pdf`: each font's name, type ("TrueType", "CID
// TrueType", "Type 3", ...) and whether it is embedded.
struct PdfFont {
    std::string name, type;
    bool embedded = false;
};
std::vector<PdfFont> pdf_fonts(const std::filesystem::path& pdf);

// The PDF's first page at `dpi` (pdftoppm), the SVG at its own size (rsvg-convert).
render::Image rasterise_pdf(const std::filesystem::path& pdf, int dpi = 100);
render::Image rasterise_svg(const std::filesystem::path& svg);

}  // namespace testkit
