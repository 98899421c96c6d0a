#include "render/gl_program.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

#include "render/shaders.h"

namespace trilab {
namespace {

const char* stage_name(GLenum stage) {
    switch (stage) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_GEOMETRY_SHADER:
            return "geometry";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        default:
            return "unknown";
    }
}

std::string shader_log(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

std::string program_log(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(length > 0 ? length : 0), '\0');
    if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

/// Compiles one stage; throws GlError with the log on failure (the shader is deleted then).
GLuint compile(const ShaderSource& source) {
    GLuint shader = glCreateShader(source.stage);
    if (shader == 0)
        throw GlError("GlProgram: glCreateShader failed for " +
                      std::string(stage_name(source.stage)) + " shader '" + source.name + "'");
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log = shader_log(shader);
        glDeleteShader(shader);
        throw GlError("GlProgram: " + std::string(stage_name(source.stage)) + " shader '" +
                      source.name + "' does not compile:\n" + log);
    }
    return shader;
}

}  // namespace

ShaderSource embedded_shader(const std::string& name) {
    const char* text = shader_source(name.c_str());
    if (!text) throw GlError("embedded_shader: no embedded shader named '" + name + "'");
    ShaderSource s;
    if (name.find(".vert") != std::string::npos) {
        s.stage = GL_VERTEX_SHADER;
    } else if (name.find(".geom") != std::string::npos) {
        s.stage = GL_GEOMETRY_SHADER;
    } else if (name.find(".frag") != std::string::npos) {
        s.stage = GL_FRAGMENT_SHADER;
    } else {
        throw GlError("embedded_shader: cannot tell the stage of '" + name +
                      "' (expected .vert, .geom or .frag in the name)");
    }
    s.name = name;
    s.text = text;
    return s;
}

ShaderSource with_defines(ShaderSource source, const std::vector<std::string>& defines) {
    if (defines.empty()) return source;
    std::string lines, names;
    for (const std::string& d : defines) {
        lines += "#define " + d + "\n";
        names += (names.empty() ? "" : ", ") + d;
    }
    std::size_t at = 0;
    std::size_t version = source.text.find("#version");
    if (version != std::string::npos) {
        std::size_t end = source.text.find('\n', version);
        at = end == std::string::npos ? source.text.size() : end + 1;
        if (end == std::string::npos) lines = "\n" + lines;
    }
    // Keep the original line numbers in driver messages after the inserted block.
    lines +=
        "#line " +
        std::to_string(std::count(source.text.begin(), source.text.begin() + long(at), '\n') + 1) +
        "\n";
    source.text.insert(at, lines);
    source.name += " [" + names + "]";
    return source;
}

GlProgram::GlProgram(const std::vector<ShaderSource>& stages) {
    std::vector<GLuint> shaders;
    auto delete_shaders = [&shaders] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    try {
        for (const ShaderSource& stage : stages) shaders.push_back(compile(stage));
    } catch (...) {
        delete_shaders();
        throw;
    }
    std::string names;
    for (const ShaderSource& stage : stages) names += (names.empty() ? "" : ", ") + stage.name;

    id_ = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(id_, s);
    glLinkProgram(id_);
    for (GLuint s : shaders) glDetachShader(id_, s);
    delete_shaders();
    GLint ok = GL_FALSE;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        std::string log = program_log(id_);
        release();
        throw GlError("GlProgram: program (" + names + ") does not link:\n" + log);
    }
}

GlProgram::~GlProgram() {
    release();
}

GlProgram::GlProgram(GlProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
    if (this != &other) {
        release();
        id_ = std::exchange(other.id_, 0);
    }
    return *this;
}

void GlProgram::release() {
    if (id_ != 0) glDeleteProgram(id_);
    id_ = 0;
}

void GlProgram::use() const {
    glUseProgram(id_);
}

void GlProgram::set(const char* name, int value) const {
    glUniform1i(glGetUniformLocation(id_, name), value);
}
void GlProgram::set(const char* name, float value) const {
    glUniform1f(glGetUniformLocation(id_, name), value);
}
void GlProgram::set(const char* name, const glm::vec2& value) const {
    glUniform2fv(glGetUniformLocation(id_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::vec3& value) const {
    glUniform3fv(glGetUniformLocation(id_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const std::vector<glm::vec3>& values) const {
    if (values.empty()) return;
    glUniform3fv(glGetUniformLocation(id_, name), GLsizei(values.size()),
                 glm::value_ptr(values.front()));
}
void GlProgram::set(const char* name, const glm::vec4& value) const {
    glUniform4fv(glGetUniformLocation(id_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::mat3& value) const {
    glUniformMatrix3fv(glGetUniformLocation(id_, name), 1, GL_FALSE, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::mat4& value) const {
    glUniformMatrix4fv(glGetUniformLocation(id_, name), 1, GL_FALSE, glm::value_ptr(value));
}

}  // namespace trilab
