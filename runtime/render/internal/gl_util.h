#pragma once
// Small OpenGL helpers shared by the render passes: move-only owners for GL
// object names (so a failed create() or an early return never leaks them) and
// shader compilation that reports the driver's log instead of a bare failure.
// Requires a current GL 3.3 core context (libepoxy loads the entry points).
#include <epoxy/gl.h>

#include <string>
#include <utility>

#include "core/result.h"

namespace tumble::render {

// One GL object name plus the function that deletes it. GL deletes accept 0,
// so a moved-from or default owner destroys nothing.
template <void (*kDelete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint name) : m_name(name) {}
  GlName(GlName&& other) noexcept : m_name(std::exchange(other.m_name, 0)) {}
  GlName& operator=(GlName&& other) noexcept {
    if (this != &other) {
      reset();
      m_name = std::exchange(other.m_name, 0);
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  ~GlName() { reset(); }

  GLuint get() const { return m_name; }
  void reset() {
    if (m_name != 0) kDelete(m_name);
    m_name = 0;
  }

 private:
  GLuint m_name = 0;
};

void deleteBuffer(GLuint name);
void deleteVertexArray(GLuint name);
void deleteProgram(GLuint name);
void deleteFramebuffer(GLuint name);
void deleteRenderbuffer(GLuint name);
void deleteTexture(GLuint name);

using GlBuffer = GlName<deleteBuffer>;
using GlVertexArray = GlName<deleteVertexArray>;
using GlProgram = GlName<deleteProgram>;
using GlFramebuffer = GlName<deleteFramebuffer>;
using GlRenderbuffer = GlName<deleteRenderbuffer>;
using GlTexture = GlName<deleteTexture>;

GlBuffer makeBuffer();
GlVertexArray makeVertexArray();
GlFramebuffer makeFramebuffer();
GlRenderbuffer makeRenderbuffer();
GlTexture makeTexture();

/// Compiles and links a vertex + fragment program. `name` only labels errors
/// ("shape shader: fragment: 0:12(3): error: ...").
Result<GlProgram> buildProgram(const char* name, const char* vertexSource,
                               const char* fragmentSource);

/// Location of a uniform that the shader source is known to declare. An
/// unused uniform is optimised away and yields -1; glUniform ignores -1, so
/// that is harmless and not reported.
GLint uniformLocation(const GlProgram& program, const char* uniformName);

/// Text of every pending glGetError code ("GL_OUT_OF_MEMORY ..."), empty if
/// none. Used at the few points where a failure must turn into a Status.
std::string drainGlErrors();

}  // namespace tumble::render
