#include "vector_check.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "media/png_io.hpp"

namespace testkit {
namespace {

// A channel of pixel (x, y) over white, 0..255.
double over_white(const render::Image& image, int x, int y, int channel) {
    const std::uint8_t* p = image.pixel(x, y);
    const double alpha = p[3] / 255.0;
    return p[channel] * alpha + 255.0 * (1 - alpha);
}

std::string quoted(const std::filesystem::path& path) {
    std::string q(1, '\'');
    q += path.string();
    q += '\'';
    return q;
}

render::Image read_and_remove(const std::filesystem::path& png) {
    render::Image image = media::read_png(png).image;
    std::filesystem::remove(png);
    return image;
}

}  // namespace

BlockDifference block_difference(const render::Image& expected, const render::Image& actual, int block) {
    BlockDifference d;
    std::ostringstream message;
    message << "expected " << expected.width << "x" << expected.height << ", got " << actual.width << "x"
            << actual.height;
    const int dw = std::abs(expected.width - actual.width), dh = std::abs(expected.height - actual.height);
    if (dw > 1 || dh > 1 || expected.width < block || expected.height < block) {
        d.message = message.str() + ": not comparable";
        return d;
    }
    d.comparable = true;
    const int width = std::min(expected.width, actual.width), height = std::min(expected.height, actual.height);
    std::vector<double> blocks;
    for (int by = 0; by + block <= height; by += block)
        for (int bx = 0; bx + block <= width; bx += block) {
            double largest = 0;
            for (int c = 0; c < 3; ++c) {
                double e = 0, a = 0;
                for (int y = by; y < by + block; ++y)
                    for (int x = bx; x < bx + block; ++x) e += over_white(expected, x, y, c), a += over_white(actual, x, y, c);
                largest = std::max(largest, std::abs(e - a) / (block * block));
            }
            blocks.push_back(largest);
        }
    double sum = 0;
    for (double b : blocks) sum += b;
    d.mean = sum / static_cast<double>(blocks.size());
    std::vector<double> sorted = blocks;
    std::sort(sorted.begin(), sorted.end());
    d.p99 = sorted[static_cast<std::size_t>(0.99 * static_cast<double>(sorted.size() - 1))];
    d.max = sorted.back();
    message << "; blocks of " << block << " px: mean difference " << d.mean << " (at most " << vector_mean_tolerance
            << "), 99th percentile " << d.p99 << " (at most " << vector_p99_tolerance << "), largest " << d.max;
    d.message = message.str();
    return d;
}

ToolRun run_tool(const std::string& command) {
    ToolRun run;
    std::FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    char buffer[4096];
    while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) run.output.append(buffer, n);
    const int status = ::pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

std::vector<PdfFont> pdf_fonts(const std::filesystem::path& pdf) {
    const ToolRun run = run_tool("pdffonts " + quoted(pdf));
    if (run.status != 0) throw std::runtime_error("pdffonts failed on " + pdf.string() + ": " + run.output);
    // A header, a line of dashes giving each column's width, then a row per font.
    std::istringstream lines(run.output);
    std::string header, dashes, line;
    std::getline(lines, header);
    std::getline(lines, dashes);
    std::vector<std::pair<std::size_t, std::size_t>> columns;  // start, length
    for (std::size_t i = 0; i < dashes.size();) {
        if (dashes[i] != '-') {
            ++i;
            continue;
        }
        const std::size_t start = i;
        while (i < dashes.size() && dashes[i] == '-') ++i;
        columns.emplace_back(start, i - start);
    }
    if (columns.size() < 4) throw std::runtime_error("pdffonts printed no table: " + run.output);
    auto cell = [&](const std::string& row, std::size_t k) {
        if (row.size() <= columns[k].first) return std::string();
        const std::string_view text = std::string_view(row).substr(columns[k].first, columns[k].second);
        const std::size_t last = text.find_last_not_of(' ');
        return last == std::string_view::npos ? std::string() : std::string(text.substr(0, last + 1));
    };
    std::vector<PdfFont> fonts;
    while (std::getline(lines, line))
        if (!line.empty()) fonts.push_back({cell(line, 0), cell(line, 1), cell(line, 3) == "yes"});
    return fonts;
}

render::Image rasterise_pdf(const std::filesystem::path& pdf, int dpi) {
    const std::filesystem::path stem = pdf.parent_path() / (pdf.stem().string() + "-pdftoppm");
    const ToolRun run = run_tool("pdftoppm -r " + std::to_string(dpi) + " -png -singlefile " + quoted(pdf) + " " +
                                 quoted(stem));
    if (run.status != 0) throw std::runtime_error("pdftoppm failed on " + pdf.string() + ": " + run.output);
    return read_and_remove(stem.string() + ".png");
}

render::Image rasterise_svg(const std::filesystem::path& svg) {
    const std::filesystem::path png = svg.parent_path() / (svg.stem().string() + "-rsvg.png");
    const ToolRun run = run_tool("rsvg-convert " + quoted(svg) + " -o " + quoted(png));
    if (run.status != 0) throw std::runtime_error("rsvg-convert failed on " + svg.string() + ": " + run.output);
    return read_and_remove(png);
}

}  // namespace testkit
