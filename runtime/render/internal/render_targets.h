#pragma once
// The renderer's own framebuffers. The scene is drawn into a multisampled
// colour + depth target, resolved into a single-sample colour target, and
// the HUD is drawn on top of the resolved image. That resolved image is
// "the frame": screenshots read it (so they work with the offscreen driver
// and with hidden or covered windows, where reading the window's buffer is
// undefined) and presenting copies it to the window. A frame that is only
// shown skips it: the scene goes straight into the window's framebuffer
// and the HUD is drawn there (resolveToWindow).
#include "core/result.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

class RenderTargets {
 public:
  /// (Re)creates the targets at this size; a no-op if nothing changed.
  /// samples is clamped to [1, GL_MAX_SAMPLES]; 1 means no multisampling.
  /// sceneScale (0.25..1): the scene is drawn at this fraction of the
  /// frame's width and height and scaled up (linear) into the frame, the
  /// HUD stays at full size. Below 1 the scene is not multisampled: a
  /// multisampled image cannot be resolved and scaled in one blit, and the
  /// point of scaling is to spend fewer samples.
  Status resize(int width, int height, int samples, float sceneScale = 1.0f);

  int width() const { return m_width; }
  int height() const { return m_height; }
  int sceneWidth() const { return m_sceneWidth; }
  int sceneHeight() const { return m_sceneHeight; }
  int samples() const { return m_samples; }

  /// Binds the target the scene is drawn into and sets the viewport.
  void bindScene() const;
  /// Resolves the scene into the frame and leaves the frame bound for the HUD.
  void resolve() const;
  GLuint frameFramebuffer() const { return m_frame.get(); }
  /// Copies the frame to the window's framebuffer (0).
  void blitToWindow(int windowWidth, int windowHeight) const;
  /// Instead of resolve() + blitToWindow(): the scene straight into the
  /// window's framebuffer (of the frame's size), left bound for the HUD.
  void resolveToWindow() const;

 private:
  int m_width = 0, m_height = 0, m_samples = 0, m_requestedSamples = 0;
  int m_sceneWidth = 0, m_sceneHeight = 0;
  float m_sceneScale = 1.0f;
  GlFramebuffer m_scene;      // empty when samples == 1 and unscaled: the scene draws into m_frame
  GlRenderbuffer m_sceneColor, m_sceneDepth;
  GlFramebuffer m_frame;
  GlRenderbuffer m_frameColor, m_frameDepth;
};

}  // namespace tumble::render
