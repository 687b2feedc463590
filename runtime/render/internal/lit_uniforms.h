#pragma once
// The uniforms every lit pass shares (camera, sun, ambient, fog), looked up
// and set in one place so the shape and terrain shaders stay lit alike.
#include "render/internal/camera_math.h"
#include "render/internal/environment.h"
#include "render/internal/gl_util.h"

namespace tumble::render {

struct LitUniforms {
  GLint viewProjection = -1, eye = -1, lightDirection = -1, lightColor = -1;
  GLint skyAmbient = -1, groundAmbient = -1, fogColor = -1, fogDensity = -1;
  GLint shadowCascades = -1, shadowMap = -1, shadowMatrix = -1, shadowFar = -1, shadowTexel = -1, viewForward = -1;

  /// Looks the uniforms up in `program` (names as in shaders.cpp).
  void locate(const GlProgram& program);
  /// The texture unit the shadow map is bound to (the passes use 0 and 1).
  static constexpr int kShadowUnit = 7;
  /// Sets them on the program in use (and binds the shadow map, if any).
  void apply(const FrameView& view, const Environment& environment) const;
};

}  // namespace tumble::render
