#include "render/internal/lit_uniforms.h"

namespace tumble::render {

void LitUniforms::locate(const GlProgram& program) {
  viewProjection = uniformLocation(program, "uViewProjection");
  eye = uniformLocation(program, "uEye");
  lightDirection = uniformLocation(program, "uLightDirection");
  lightColor = uniformLocation(program, "uLightColor");
  skyAmbient = uniformLocation(program, "uSkyAmbient");
  groundAmbient = uniformLocation(program, "uGroundAmbient");
  fogColor = uniformLocation(program, "uFogColor");
  fogDensity = uniformLocation(program, "uFogDensity");
}

void LitUniforms::apply(const FrameView& view, const Environment& environment) const {
  glUniformMatrix4fv(viewProjection, 1, GL_FALSE, view.viewProjection.data());  // column-major, as GL wants
  glUniform3fv(eye, 1, view.eye.data());
  glUniform3fv(lightDirection, 1, environment.lightDirection.data());
  glUniform3fv(lightColor, 1, environment.lightColor.data());
  glUniform3fv(skyAmbient, 1, environment.skyAmbient.data());
  glUniform3fv(groundAmbient, 1, environment.groundAmbient.data());
  glUniform3fv(fogColor, 1, environment.horizonColor.data());
  glUniform1f(fogDensity, environment.fogDensity_per_m);
}

}  // namespace tumble::render
