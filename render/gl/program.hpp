#pragma once
// A linked GLSL program (vertex + fragment), owned.

#include <string>

#include <glm/glm.hpp>

#include "render/gl/gl.hpp"

namespace render {

class Program {
public:
    // Compiles and links; throws std::runtime_error with the GLSL log on failure.
    Program(const char* vertex_source, const char* fragment_source);
    ~Program();
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    void use() const { glUseProgram(id_); }
    GLint uniform(const char* name) const { return glGetUniformLocation(id_, name); }
    void set(const char* name, int value) const { glUniform1i(uniform(name), value); }
    void set(const char* name, float value) const { glUniform1f(uniform(name), value); }
    void set(const char* name, const glm::vec2& value) const { glUniform2f(uniform(name), value.x, value.y); }
    void set(const char* name, const glm::vec4& value) const;
    void set(const char* name, const glm::mat4& value) const;

private:
    GLuint id_ = 0;
};

// A program with one vertex array and one vertex buffer refilled per draw:
// what each batch kind (shapes, text) draws with. Lives as long as the context.
struct StreamPipeline {
    Program program;
    GLuint vao = 0, vbo = 0;
    StreamPipeline(const char* vertex_source, const char* fragment_source);
};

}  // namespace render
