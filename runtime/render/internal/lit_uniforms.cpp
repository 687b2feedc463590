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
  shadowCascades = uniformLocation(program, "uShadowCascades");
  shadowMap = uniformLocation(program, "uShadowMap");
  shadowMatrix = uniformLocation(program, "uShadowMatrix");
  shadowFar = uniformLocation(program, "uShadowFar");
  shadowTexel = uniformLocation(program, "uShadowTexel");
  viewForward = uniformLocation(program, "uViewForward");
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
  const int cascades = environment.shadowTexture != 0 ? environment.shadowCascades : 0;
  glUniform1i(shadowCascades, cascades);
  glUniform1i(shadowMap, kShadowUnit);
  glUniform3fv(viewForward, 1, view.forward.data());
  if (cascades > 0) {
    glUniformMatrix4fv(shadowMatrix, cascades, GL_FALSE, environment.shadowMatrices[0].data());
    glUniform3fv(shadowFar, 1, environment.shadowFar_m.data());
    glUniform3fv(shadowTexel, 1, environment.shadowTexel_m.data());
  }
  glActiveTexture(GL_TEXTURE0 + kShadowUnit);
  glBindTexture(GL_TEXTURE_2D_ARRAY, cascades > 0 ? environment.shadowTexture : 0);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace tumble::render
