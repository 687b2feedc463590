#include "render/internal/sky_pass.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/internal/shaders.h"
#include "render/internal/sky_model.h"

namespace tumble::render {

namespace {

constexpr int kPlasmaSize = 256;
constexpr std::uint32_t kPlasmaSeed = 1994;

}  // namespace

Status SkyPass::init() {
  auto program = buildProgram("sky shader", shaders::kSkyVertex, shaders::kSkyFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_emptyVao = makeVertexArray();
  m_right = uniformLocation(m_program, "uRight");
  m_up = uniformLocation(m_program, "uUp");
  m_forward = uniformLocation(m_program, "uForward");
  m_tanHalfFov = uniformLocation(m_program, "uTanHalfFov");
  m_sky = uniformLocation(m_program, "uSky");
  m_cloudTexture = uniformLocation(m_program, "uClouds");
  m_cloudCover = uniformLocation(m_program, "uCloudCover");
  m_cloudOffset = uniformLocation(m_program, "uCloudOffset");
  m_cloudColor = uniformLocation(m_program, "uCloudColor");
  m_cloudShadow = uniformLocation(m_program, "uCloudShadow");
  m_horizon = uniformLocation(m_program, "uHorizonColor");
  m_flash = uniformLocation(m_program, "uFlash");

  m_cube = makeTexture();
  glBindTexture(GL_TEXTURE_CUBE_MAP, m_cube.get());
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);

  return Ok{};
}

void SkyPass::makeClouds() {
  {
    const std::vector<std::uint8_t> plasma = buildPlasma(kPlasmaSize, kPlasmaSeed);
    m_clouds = makeTexture();
    glBindTexture(GL_TEXTURE_2D, m_clouds.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, kPlasmaSize, kPlasmaSize, 0, GL_RED, GL_UNSIGNED_BYTE, plasma.data());
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
}

void SkyPass::rebuildCubeIfChanged(const Environment& e) {
  std::array<float, 17> key{};
  int k = 0;
  for (const Eigen::Vector3f* v : {&e.zenithColor, &e.horizonColor, &e.groundColor, &e.lightDirection, &e.lightColor})
    for (int i = 0; i < 3; ++i) key[k++] = (*v)[i];
  key[k++] = e.sunDisc;
  key[k++] = float(m_cubeSize);
  // Changes below 1/4096 are invisible in 8-bit colour: keep the cube.
  bool same = m_hasCube;
  for (std::size_t i = 0; same && i < key.size(); ++i) same = std::abs(key[i] - m_cubeKey[i]) < 1.0f / 4096.0f;
  if (same) return;
  m_cubeKey = key;
  m_hasCube = true;
  ++m_cubeBuilds;
  const std::vector<float> texels = buildSkyCube(e, m_cubeSize);
  const std::size_t faceFloats = static_cast<std::size_t>(m_cubeSize) * m_cubeSize * 3;
  glBindTexture(GL_TEXTURE_CUBE_MAP, m_cube.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (int face = 0; face < 6; ++face) {
    glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_RGB16F, m_cubeSize, m_cubeSize, 0, GL_RGB, GL_FLOAT,
                 texels.data() + face * faceFloats);
  }
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
}

void SkyPass::draw(const FrameView& view, const Environment& environment, int cubeSize, bool cloudsOn,
                   float flash) {
  m_cubeSize = std::clamp(cubeSize, 16, 1024);
  rebuildCubeIfChanged(environment);
  const bool clouds = cloudsOn && environment.cloudCover > 0.0f;
  if (clouds && m_clouds.get() == 0) makeClouds();
  glUseProgram(m_program.get());
  glUniform3fv(m_right, 1, view.right.data());
  glUniform3fv(m_up, 1, view.up.data());
  glUniform3fv(m_forward, 1, view.forward.data());
  glUniform2f(m_tanHalfFov, view.tanHalfFovX, view.tanHalfFovY);
  glUniform1i(m_sky, 0);
  glUniform1i(m_cloudTexture, 1);
  glUniform1f(m_cloudCover, clouds ? environment.cloudCover : 0.0f);
  glUniform2fv(m_cloudOffset, 1, environment.cloudOffset_m.data());
  glUniform3fv(m_cloudColor, 1, environment.cloudColor.data());
  glUniform3fv(m_cloudShadow, 1, environment.cloudShadowColor.data());
  glUniform3fv(m_horizon, 1, environment.horizonColor.data());
  glUniform1f(m_flash, std::clamp(flash, 0.0f, 1.0f));
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, clouds ? m_clouds.get() : 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_CUBE_MAP, m_cube.get());

  // Background: drawn after the opaque passes at the far plane (depth 1),
  // so the depth test keeps it to the pixels nothing else covered; no depth
  // write.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glBindVertexArray(m_emptyVao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace tumble::render
