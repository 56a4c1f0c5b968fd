#include "render/gl/program.hpp"

#include <stdexcept>

#include <glm/gtc/type_ptr.hpp>

#include "render/gl/gl_context.hpp"

namespace render {
namespace {

GLuint compile(GLenum kind, const char* source) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        throw std::runtime_error(std::string("GLSL compile error: ") + log);
    }
    return shader;
}

}  // namespace

Program::Program(const char* vertex_source, const char* fragment_source) {
    GlContext::get();
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source);
    id_ = glCreateProgram();
    glAttachShader(id_, vs);
    glAttachShader(id_, fs);
    glLinkProgram(id_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(id_, sizeof log, nullptr, log);
        glDeleteProgram(id_);
        throw std::runtime_error(std::string("GLSL link error: ") + log);
    }
}

Program::~Program() { glDeleteProgram(id_); }

void Program::set(const char* name, const glm::vec4& value) const {
    glUniform4fv(uniform(name), 1, glm::value_ptr(value));
}

void Program::set(const char* name, const glm::mat4& value) const {
    glUniformMatrix4fv(uniform(name), 1, GL_FALSE, glm::value_ptr(value));
}

StreamPipeline::StreamPipeline(const char* vertex_source, const char* fragment_source)
    : program(vertex_source, fragment_source) {
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
}

}  // namespace render
