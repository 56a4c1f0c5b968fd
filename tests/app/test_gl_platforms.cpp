// Where GL comes from (--gl): the platforms record themselves, and figures
// render where OSMesa is gone (Mesa removed it in 25.1) or EGL is missing.
// A library is hidden by a mount namespace in which /dev/null is bound over
// it (unshare --map-root-user --mount: root, or an unprivileged user where
// the kernel allows user namespaces).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "figgen_run.hpp"
#include "golden_cases.hpp"
#include "image_check.hpp"
#include "render/gl/gl_context.hpp"
#include "media/png_io.hpp"

namespace fs = std::filesystem;
using testkit::Run;

namespace {

// Where the loader finds `soname` (ldconfig's cache); empty if nowhere.
std::string library_path(const std::string& soname) {
    const Run run = testkit::run_command("/sbin/ldconfig -p");
    std::istringstream lines(run.output);
    for (std::string line; std::getline(lines, line);) {
        const auto arrow = line.find(" => ");
        if (line.find(soname + " (") != std::string::npos && line.find("x86-64") != std::string::npos &&
            arrow != std::string::npos)
            return line.substr(arrow + 4);
    }
    return {};
}

struct Hidden {
    bool possible = true;  // false: no mount namespace here (the reason is in run.output)
    Run run;
};

// Runs `figgen args` with the libraries `sonames` hidden.
Hidden figgen_without(const std::vector<std::string>& sonames, const std::string& args) {
    std::string mounts;
    for (const std::string& soname : sonames) {
        const std::string path = library_path(soname);
        INFO(soname << " is not in ldconfig's cache");
        REQUIRE_FALSE(path.empty());
        mounts += "mount --bind /dev/null " + path + " && ";
    }
    Hidden h;
    h.run = testkit::run_command("unshare --map-root-user --mount sh -c '" + mounts + "exec " FIGGEN_EXE " " + args +
                                 "'");
    h.possible = h.run.output.rfind("unshare:", 0) != 0 && h.run.output.rfind("mount:", 0) != 0;
    return h;
}

// The lines figgen said on its own behalf ("figgen: ...").
std::vector<std::string> figgen_lines(const std::string& output) {
    std::vector<std::string> said;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("figgen: ", 0) == 0) said.push_back(line);
    return said;
}

nlohmann::json metadata(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

std::string golden_hash(const std::string& id) {
    std::ifstream in(fs::path(FIGGEN_TEST_GOLDEN_DIR) / (id + ".sha256"));
    std::string hash;
    std::getline(in, hash);
    return hash;
}

}  // namespace

TEST_CASE("each --gl platform draws and says so in the JSON", "[gl]") {
    const fs::path out = testkit::fresh_dir("gl-platforms");
    std::string first_pixels;
    for (const std::string platform : {"osmesa", "egl", "egl-device", "auto"}) {
        INFO("--gl " << platform);
        const fs::path dir = out / platform;
        const Run run = testkit::figgen("render tc7-7 --format png --gl " + platform + " --out " + dir.string());
        INFO(run.output);
        REQUIRE(run.status == 0);
        CHECK(figgen_lines(run.output).empty());  // no fallback here: every platform works
        const nlohmann::json renderer = metadata(dir / "tc7-7.json")["renderer"];
        CHECK(renderer["platform"] == (platform == "auto" ? "egl" : platform));
        CHECK(renderer["samples"] == 4);
        CHECK(render::is_llvmpipe(renderer["gl_renderer"]));
        CHECK(renderer["software"] == true);
        CHECK_FALSE(renderer.contains("debug"));
        // Mesa's software device, the one device of a machine without a GPU.
        if (platform == "egl-device") CHECK(renderer["device"] == "software");
        else CHECK_FALSE(renderer.contains("device"));
        const std::string pixels = testkit::pixel_hash(media::read_png(dir / "tc7-7.png").image);
        if (first_pixels.empty()) first_pixels = pixels;
        CHECK(pixels == first_pixels);
    }
}

TEST_CASE("with libOSMesa hidden figures render through EGL with the golden pixels", "[gl]") {
    const fs::path out = testkit::fresh_dir("without-osmesa");
    std::ostringstream args;
    args << "render tc7-2 sf87-3 pl-lsys-3d --no-video --scale " << testkit::golden_scale << " --out " << out.string();
    const Hidden h = figgen_without({"libOSMesa.so.8"}, args.str());
    INFO(h.run.output);
    if (!h.possible) {
        WARN("no mount namespace here, so libOSMesa cannot be hidden: " << h.run.output);
        return;
    }
    REQUIRE(h.run.status == 0);
    CHECK(figgen_lines(h.run.output).empty());  // auto took EGL: nothing to say
    for (const std::string id : {"tc7-2", "sf87-3", "pl-lsys-3d"}) {
        INFO(id);
        CHECK(metadata(out / (id + ".json"))["renderer"]["platform"] == "egl");
        CHECK(testkit::pixel_hash(media::read_png(out / (id + ".png")).image) == golden_hash(id));
    }
    // And asked for by name, OSMesa is refused in one line naming its package.
    const Hidden osmesa = figgen_without({"libOSMesa.so.8"}, "render tc7-7 --format png --gl osmesa --out " +
                                                                 (out / "osmesa").string());
    INFO(osmesa.run.output);
    CHECK(osmesa.run.status == 1);
    const std::vector<std::string> said = figgen_lines(osmesa.run.output);
    REQUIRE(said.size() == 1);
    CHECK(said[0].find("libOSMesa.so.8") != std::string::npos);
    CHECK(said[0].find("install Debian's libosmesa6") != std::string::npos);
    CHECK_FALSE(fs::exists(out / "osmesa" / "tc7-7.png"));
}

TEST_CASE("with libEGL hidden auto falls back to OSMesa in one line and egl is refused", "[gl]") {
    const fs::path out = testkit::fresh_dir("without-egl");
    const Hidden h = figgen_without({"libEGL.so.1"}, "render tc7-7 --format png --out " + (out / "auto").string());
    INFO(h.run.output);
    if (!h.possible) {
        WARN("no mount namespace here, so libEGL cannot be hidden: " << h.run.output);
        return;
    }
    REQUIRE(h.run.status == 0);
    const std::vector<std::string> said = figgen_lines(h.run.output);
    REQUIRE(said.size() == 1);
    CHECK(said[0].rfind("figgen: note: drawing with OSMesa: cannot load libEGL.so.1", 0) == 0);
    CHECK(said[0].find("install Debian's libegl1") != std::string::npos);
    CHECK(metadata(out / "auto" / "tc7-7.json")["renderer"]["platform"] == "osmesa");

    const Hidden egl = figgen_without({"libEGL.so.1"}, "render tc7-7 --format png --gl egl --out " +
                                                           (out / "egl").string());
    INFO(egl.run.output);
    CHECK(egl.run.status == 1);
    CHECK(figgen_lines(egl.run.output).size() == 1);
    CHECK(egl.run.output.find("install Debian's libegl1") != std::string::npos);

    // With neither, one line names both.
    const Hidden neither = figgen_without({"libEGL.so.1", "libOSMesa.so.8"},
                                          "render tc7-7 --format png --out " + (out / "neither").string());
    INFO(neither.run.output);
    CHECK(neither.run.status == 1);
    const std::vector<std::string> none = figgen_lines(neither.run.output);
    REQUIRE(none.size() == 1);
    CHECK(none[0].find("libegl1") != std::string::npos);
    CHECK(none[0].find("libosmesa6") != std::string::npos);
    CHECK_FALSE(fs::exists(out / "neither" / "tc7-7.png"));
}

TEST_CASE("a wrong --gl, FIGGEN_GL or --gl-device is refused before anything runs", "[gl][cli]") {
    const fs::path out = testkit::fresh_dir("gl-refused");
    struct Case {
        std::string environment, args, expected;
    };
    const std::vector<Case> cases = {
        {"", "--gl vulkan", "--gl vulkan is not allowed: use auto, osmesa, egl or egl-device"},
        {"FIGGEN_GL=glx", "", "FIGGEN_GL=glx is not allowed: use auto, osmesa, egl or egl-device"},
        {"", "--gl egl --gl-device 1", "--gl-device 1 is not allowed with --gl egl: use it with --gl egl-device"},
        {"", "--gl egl-device --gl-device 7",
         "--gl-device 7 is not allowed: EGL's device platform has "},
        {"", "--gl-device -1", "--gl-device"},
    };
    for (const Case& c : cases) {
        INFO(c.environment << " " << c.args);
        const Run run = testkit::figgen_env(c.environment, "render tc7-7 --format png --out " + out.string() + " " + c.args);
        INFO(run.output);
        CHECK(run.status == 2);
        CHECK(run.lines() == 1);
        CHECK(run.output.find(c.expected) != std::string::npos);
    }
    CHECK(fs::is_empty(out));
    // --gl given wins over FIGGEN_GL.
    const Run run = testkit::figgen_env("FIGGEN_GL=glx", "render tc7-7 --format png --gl osmesa --out " + out.string());
    INFO(run.output);
    CHECK(run.status == 0);
    CHECK(metadata(out / "tc7-7.json")["renderer"]["platform"] == "osmesa");
}

namespace {

// Every catalog figure's id, a cheap one first.
std::string catalog_ids() {
    std::string ids = "tc7-7";
    for (const auto& e : fs::directory_iterator(fs::path(FIGGEN_SOURCE_DIR) / "figures"))
        if (e.path().extension() == ".toml" && e.path().stem() != "tc7-7") ids += " " + e.path().stem().string();
    return ids;
}

}  // namespace

TEST_CASE("below GL 3.3 every figure is refused in one line, by no signal", "[gl]") {
    // The golden tests draw every figure with Mesa offering exactly 3.3 (the
    // least figgen takes); one below, no platform gives figgen a context.
    for (const std::string platform : {"auto", "osmesa", "egl", "egl-device"}) {
        INFO("--gl " << platform);
        const fs::path out = testkit::fresh_dir("gl-3.2-" + platform);
        const Run run = testkit::figgen_env("MESA_GL_VERSION_OVERRIDE=3.2",
                                            "render " + catalog_ids() + " --no-video --gl " + platform + " --out " +
                                                out.string());
        INFO(run.output);
        CHECK(run.status == 1);  // an exit, not a signal (run_command gives -1 for one)
        const std::vector<std::string> said = figgen_lines(run.output);
        REQUIRE(said.size() == 1);
        CHECK(said[0].find("3.3") != std::string::npos);
        CHECK(run.lines() == 1);
        CHECK(fs::is_empty(out));
    }
}

TEST_CASE("a renderer other than llvmpipe that cannot draw figgen's canvases is refused in one line", "[gl]") {
    // Mesa's softpipe offers GL 3.3 without multisampling: auto finds no
    // llvmpipe, goes on to it as it would to a GPU, and refuses it for its
    // samples; asked for by name, the same.
    for (const std::string platform : {"auto", "egl", "osmesa"}) {
        INFO("--gl " << platform);
        const fs::path out = testkit::fresh_dir("softpipe-" + platform);
        const Run run = testkit::figgen_env("GALLIUM_DRIVER=softpipe", "render tc7-7 --no-video --gl " + platform +
                                                                            " --out " + out.string());
        INFO(run.output);
        CHECK(run.status == 1);
        REQUIRE(figgen_lines(run.output).size() == 1);
        CHECK(run.lines() == 1);
        CHECK(run.output.find("softpipe") != std::string::npos);
        CHECK(run.output.find("samples a pixel; figgen needs 4") != std::string::npos);
        CHECK(fs::is_empty(out));
    }
}
