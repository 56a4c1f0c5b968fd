// A debug context (FIGGEN_GL_DEBUG=1) turns what the GL reports into a
// failure: registered by tests/CMakeLists.txt with that variable, once per
// platform, so that the context of this process is made with it.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>

#include "render/gl/gl.hpp"
#include "render/gl/gl_context.hpp"

using Catch::Matchers::Contains;

TEST_CASE("a debug context fails on a GL error and names the call", "[.gl_debug]") {
    const char* asked = std::getenv("FIGGEN_GL_DEBUG");
    INFO("run with FIGGEN_GL_DEBUG=1 (tests/CMakeLists.txt does)");
    REQUIRE((asked && std::string(asked) == "1"));
    const render::GlContext& gl = render::GlContext::get();
    REQUIRE(gl.debug());
    CHECK_NOTHROW(render::check_gl("nothing"));
    // GL_INVALID_ENUM: what llvmpipe records and goes on from.
    glEnable(GLenum(0x7FFF));
    CHECK_THROWS_WITH(render::check_gl("a wrong enum"),
                      Contains("FIGGEN_GL_DEBUG=1: GL error") && Contains("(by a wrong enum)"));
    // Reported once: the next check finds nothing, nor does glGetError.
    CHECK_NOTHROW(render::check_gl("the next call"));
    CHECK(glGetError() == GL_NO_ERROR);
    // GL_INVALID_OPERATION: a draw with no program bound.
    glDrawArrays(GL_TRIANGLES, 0, 3);
    CHECK_THROWS_WITH(render::check_gl("a draw without a program"), Contains("GL error"));
}
