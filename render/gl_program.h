#pragma once
// GlProgram: an OpenGL shader program built from GLSL sources. Compile and link failures are
// reported as GlError exceptions carrying the driver's info log, never printed and ignored.
// Every function here needs a current OpenGL 3.3 core context with glad loaded.
#include <glad/gl.h>

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/errors.h"

namespace trilab {

/// A shader that does not compile, a program that does not link, or a missing embedded
/// shader. The message names the shader (or program) and contains the driver's log.
class GlError : public Error {
public:
    using Error::Error;
};

/// One stage of a program: its GL stage, a name for messages, and the GLSL text.
struct ShaderSource {
    GLenum stage = GL_VERTEX_SHADER;  ///< GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, ...
    std::string name;
    std::string text;
};

/// The embedded shader file `name` (see render/shaders.h), its stage taken from the name:
/// ".vert" vertex, ".geom" geometry, ".frag" fragment (e.g. "mesh.frag.glsl"). Throws
/// GlError when no shader of that name is embedded or the stage cannot be told.
ShaderSource embedded_shader(const std::string& name);

/// `source` with "#define NAME" lines inserted after its #version line (or at the top when
/// it has none), for compiling variants of one shader file. Names may carry a value
/// ("SAMPLES 4"). The source name gets the defines appended in brackets for messages.
ShaderSource with_defines(ShaderSource source, const std::vector<std::string>& defines);

/// Owns one linked GL program object. Move-only; the default-constructed object is empty.
class GlProgram {
public:
    GlProgram() = default;
    /// Compiles every stage and links them. Throws GlError naming the failing stage (or the
    /// program, for link errors) with the info log; nothing is leaked then.
    explicit GlProgram(const std::vector<ShaderSource>& stages);
    ~GlProgram();
    GlProgram(GlProgram&& other) noexcept;
    GlProgram& operator=(GlProgram&& other) noexcept;
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    GLuint id() const { return id_; }
    bool is_valid() const { return id_ != 0; }
    void use() const;

    // Uniform setters for the program in use (call use() first). A name the linker removed
    // as unused has no location and is ignored, so optional uniforms need no special case.
    void set(const char* name, int value) const;
    void set(const char* name, float value) const;
    void set(const char* name, const glm::vec2& value) const;
    void set(const char* name, const glm::vec3& value) const;
    void set(const char* name, const glm::vec4& value) const;
    void set(const char* name, const glm::mat3& value) const;
    void set(const char* name, const glm::mat4& value) const;
    /// A vec3 array uniform (`name` without "[0]"): its first values.size() entries.
    void set(const char* name, const std::vector<glm::vec3>& values) const;

private:
    void release();
    GLuint id_ = 0;
};

}  // namespace trilab
