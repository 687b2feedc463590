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

  /// Looks the uniforms up in `program` (names as in shaders.cpp).
  void locate(const GlProgram& program);
  /// Sets them on the program in use.
  void apply(const FrameView& view, const Environment& environment) const;
};

}  // namespace tumble::render
