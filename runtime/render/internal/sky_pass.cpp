#include "render/internal/sky_pass.h"

#include "render/internal/shaders.h"

namespace tumble::render {

Status SkyPass::init() {
  auto program = buildProgram("sky shader", shaders::kSkyVertex, shaders::kSkyFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_emptyVao = makeVertexArray();
  m_right = uniformLocation(m_program, "uRight");
  m_up = uniformLocation(m_program, "uUp");
  m_forward = uniformLocation(m_program, "uForward");
  m_tanHalfFov = uniformLocation(m_program, "uTanHalfFov");
  m_zenith = uniformLocation(m_program, "uZenithColor");
  m_horizon = uniformLocation(m_program, "uHorizonColor");
  m_ground = uniformLocation(m_program, "uGroundColor");
  m_lightDirection = uniformLocation(m_program, "uLightDirection");
  m_lightColor = uniformLocation(m_program, "uLightColor");
  return Ok{};
}

void SkyPass::draw(const FrameView& view, const Environment& environment) const {
  glUseProgram(m_program.get());
  glUniform3fv(m_right, 1, view.right.data());
  glUniform3fv(m_up, 1, view.up.data());
  glUniform3fv(m_forward, 1, view.forward.data());
  glUniform2f(m_tanHalfFov, view.tanHalfFovX, view.tanHalfFovY);
  glUniform3fv(m_zenith, 1, environment.zenithColor.data());
  glUniform3fv(m_horizon, 1, environment.horizonColor.data());
  glUniform3fv(m_ground, 1, environment.groundColor.data());
  glUniform3fv(m_lightDirection, 1, environment.lightDirection.data());
  glUniform3fv(m_lightColor, 1, environment.lightColor.data());

  // Background: no depth test and no depth write, everything else draws over it.
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindVertexArray(m_emptyVao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
}

}  // namespace tumble::render
