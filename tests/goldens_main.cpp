// `make goldens`: renders every golden case and rewrites tests/golden/.
// Run by hand after a deliberate change to how things look; CI never runs it.
// figgen_goldens [DIR [NAME...]]: only the named cases when names are given.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "golden_cases.hpp"
#include "image_check.hpp"
#include "render/gl/gl_context.hpp"

int main(int argc, char** argv) {
    const char* dir = argc > 1 ? argv[1] : FIGGEN_TEST_GOLDEN_DIR;
    const std::vector<std::string> only(argv + std::min(argc, 2), argv + argc);
    try {
        for (const auto& c : testkit::golden_cases()) {
            if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
            testkit::Rendered r = c.make("");
            std::string renderer, version;
            if (c.figure) {
                renderer = r.meta["renderer"]["gl_renderer"];
                version = r.meta["renderer"]["gl_version"];
                std::ofstream out(std::filesystem::path(dir) / (c.name + ".json"));
                out << testkit::comparable_metadata(r.meta).dump(2) << "\n";
                if (!out) throw std::runtime_error("cannot write the metadata of " + c.name);
            } else {
                renderer = render::GlContext::get().renderer();
                version = render::GlContext::get().version();
            }
            testkit::write_golden(dir, c.name, r.image, renderer, version);
            std::printf("wrote %s/%s.png and .sha256\n", dir, c.name.c_str());
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "figgen_goldens: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
