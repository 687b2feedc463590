#include "render/internal/render_targets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace tumble::render {

namespace {

GlRenderbuffer makeStorage(GLenum format, int samples, int width, int height) {
  GlRenderbuffer buffer = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, buffer.get());
  if (samples > 1) {
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, width, height);
  } else {
    glRenderbufferStorage(GL_RENDERBUFFER, format, width, height);
  }
  return buffer;
}

Status checkComplete(const char* name) {
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_COMPLETE) return Ok{};
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", status);
  return makeError(std::string(name) + " framebuffer is incomplete (glCheckFramebufferStatus " +
                   code + ") " + drainGlErrors());
}

}  // namespace

Status RenderTargets::resize(int width, int height, int samples, float sceneScale) {
  sceneScale = std::clamp(sceneScale, 0.25f, 1.0f);
  if (width == m_width && height == m_height && samples == m_requestedSamples && sceneScale == m_sceneScale &&
      m_frame.get()) {
    return Ok{};
  }
  if (width <= 0 || height <= 0) {
    return makeError("framebuffer size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is invalid");
  }
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  const int sceneWidth = std::max(1, static_cast<int>(std::lround(width * sceneScale)));
  const int sceneHeight = std::max(1, static_cast<int>(std::lround(height * sceneScale)));
  const bool scaled = sceneWidth != width || sceneHeight != height;
  const int usedSamples = scaled ? 1 : std::clamp(samples, 1, std::max(1, static_cast<int>(maxSamples)));

  m_scene.reset();
  m_sceneColor.reset();
  m_sceneDepth.reset();
  m_frameDepth.reset();

  m_frame = makeFramebuffer();
  m_frameColor = makeStorage(GL_RGBA8, 1, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, m_frame.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                            m_frameColor.get());
  if (usedSamples == 1 && !scaled) {
    m_frameDepth = makeStorage(GL_DEPTH_COMPONENT24, 1, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              m_frameDepth.get());
  }
  if (Status s = checkComplete("frame"); !s) return s;

  if (usedSamples > 1 || scaled) {
    m_scene = makeFramebuffer();
    m_sceneColor = makeStorage(GL_RGBA8, usedSamples, sceneWidth, sceneHeight);
    m_sceneDepth = makeStorage(GL_DEPTH_COMPONENT24, usedSamples, sceneWidth, sceneHeight);
    glBindFramebuffer(GL_FRAMEBUFFER, m_scene.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              m_sceneColor.get());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              m_sceneDepth.get());
    if (Status s = checkComplete("multisampled scene"); !s) return s;
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  m_width = width;
  m_height = height;
  m_sceneWidth = sceneWidth;
  m_sceneHeight = sceneHeight;
  m_sceneScale = sceneScale;
  m_samples = usedSamples;
  m_requestedSamples = samples;
  return Ok{};
}

void RenderTargets::bindScene() const {
  glBindFramebuffer(GL_FRAMEBUFFER, m_scene.get() ? m_scene.get() : m_frame.get());
  glViewport(0, 0, m_sceneWidth, m_sceneHeight);
}

void RenderTargets::resolve() const {
  if (m_scene.get()) {
    const bool scaled = m_sceneWidth != m_width || m_sceneHeight != m_height;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, m_scene.get());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m_frame.get());
    glBlitFramebuffer(0, 0, m_sceneWidth, m_sceneHeight, 0, 0, m_width, m_height, GL_COLOR_BUFFER_BIT,
                      scaled ? GL_LINEAR : GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, m_frame.get());
  glViewport(0, 0, m_width, m_height);
}

void RenderTargets::resolveToWindow() const {
  const bool scaled = m_sceneWidth != m_width || m_sceneHeight != m_height;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m_scene.get() ? m_scene.get() : m_frame.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, m_sceneWidth, m_sceneHeight, 0, 0, m_width, m_height, GL_COLOR_BUFFER_BIT,
                    scaled ? GL_LINEAR : GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, m_width, m_height);
}

void RenderTargets::blitToWindow(int windowWidth, int windowHeight) const {
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m_frame.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  // Sizes match except for the one frame after a window resize.
  glBlitFramebuffer(0, 0, m_width, m_height, 0, 0, windowWidth, windowHeight, GL_COLOR_BUFFER_BIT,
                    GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tumble::render
