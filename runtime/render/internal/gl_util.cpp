#include "render/internal/gl_util.h"

#include <vector>

namespace tumble::render {

void deleteBuffer(GLuint name) { glDeleteBuffers(1, &name); }
void deleteVertexArray(GLuint name) { glDeleteVertexArrays(1, &name); }
void deleteProgram(GLuint name) { glDeleteProgram(name); }
void deleteFramebuffer(GLuint name) { glDeleteFramebuffers(1, &name); }
void deleteRenderbuffer(GLuint name) { glDeleteRenderbuffers(1, &name); }
void deleteTexture(GLuint name) { glDeleteTextures(1, &name); }

GlBuffer makeBuffer() {
  GLuint name = 0;
  glGenBuffers(1, &name);
  return GlBuffer(name);
}

GlVertexArray makeVertexArray() {
  GLuint name = 0;
  glGenVertexArrays(1, &name);
  return GlVertexArray(name);
}

GlFramebuffer makeFramebuffer() {
  GLuint name = 0;
  glGenFramebuffers(1, &name);
  return GlFramebuffer(name);
}

GlTexture makeTexture() {
  GLuint name = 0;
  glGenTextures(1, &name);
  return GlTexture(name);
}

GlRenderbuffer makeRenderbuffer() {
  GLuint name = 0;
  glGenRenderbuffers(1, &name);
  return GlRenderbuffer(name);
}

namespace {

// Shader and program objects share the same shape of info-log query.
template <void (*kGetiv)(GLuint, GLenum, GLint*), void (*kGetLog)(GLuint, GLsizei, GLsizei*, GLchar*)>
std::string infoLog(GLuint object) {
  GLint length = 0;
  kGetiv(object, GL_INFO_LOG_LENGTH, &length);
  if (length <= 1) return "(no log)";
  std::vector<char> text(static_cast<std::size_t>(length));
  kGetLog(object, length, nullptr, text.data());
  return std::string(text.data());
}

void getShaderiv(GLuint s, GLenum p, GLint* v) { glGetShaderiv(s, p, v); }
void getShaderLog(GLuint s, GLsizei n, GLsizei* l, GLchar* t) { glGetShaderInfoLog(s, n, l, t); }
void getProgramiv(GLuint s, GLenum p, GLint* v) { glGetProgramiv(s, p, v); }
void getProgramLog(GLuint s, GLsizei n, GLsizei* l, GLchar* t) { glGetProgramInfoLog(s, n, l, t); }

void deleteShader(GLuint name) { glDeleteShader(name); }
using GlShader = GlName<deleteShader>;

Result<GlShader> compileShader(const char* name, GLenum stage, const char* source) {
  GlShader shader(glCreateShader(stage));
  glShaderSource(shader.get(), 1, &source, nullptr);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const char* stageName = stage == GL_VERTEX_SHADER ? "vertex" : "fragment";
    return makeError(std::string(name) + ": " + stageName + " shader did not compile: " +
                     infoLog<getShaderiv, getShaderLog>(shader.get()));
  }
  return shader;
}

}  // namespace

Result<GlProgram> buildProgram(const char* name, const char* vertexSource,
                               const char* fragmentSource) {
  auto vertex = compileShader(name, GL_VERTEX_SHADER, vertexSource);
  if (!vertex) return makeError(vertex.error());
  auto fragment = compileShader(name, GL_FRAGMENT_SHADER, fragmentSource);
  if (!fragment) return makeError(fragment.error());

  GlProgram program(glCreateProgram());
  glAttachShader(program.get(), vertex->get());
  glAttachShader(program.get(), fragment->get());
  glLinkProgram(program.get());
  // Detach so the shader objects are really freed when their owners go.
  glDetachShader(program.get(), vertex->get());
  glDetachShader(program.get(), fragment->get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    return makeError(std::string(name) + ": program did not link: " +
                     infoLog<getProgramiv, getProgramLog>(program.get()));
  }
  return program;
}

GLint uniformLocation(const GlProgram& program, const char* uniformName) {
  return glGetUniformLocation(program.get(), uniformName);
}

std::string drainGlErrors() {
  std::string text;
  // Bounded: after a lost context some drivers report errors forever.
  for (int i = 0; i < 16; ++i) {
    const GLenum code = glGetError();
    if (code == GL_NO_ERROR) break;
    const char* name = "GL error";
    switch (code) {
      case GL_INVALID_ENUM: name = "GL_INVALID_ENUM"; break;
      case GL_INVALID_VALUE: name = "GL_INVALID_VALUE"; break;
      case GL_INVALID_OPERATION: name = "GL_INVALID_OPERATION"; break;
      case GL_INVALID_FRAMEBUFFER_OPERATION: name = "GL_INVALID_FRAMEBUFFER_OPERATION"; break;
      case GL_OUT_OF_MEMORY: name = "GL_OUT_OF_MEMORY"; break;
      default: break;
    }
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

}  // namespace tumble::render
