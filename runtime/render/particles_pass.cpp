#include "render/internal/particles_pass.h"

#include <algorithm>
#include <cstddef>
#include <numeric>

namespace tumble::render {

namespace {

constexpr unsigned kAttribCorner = 0;
constexpr unsigned kAttribPosition = 1;
constexpr unsigned kAttribSize = 2;
constexpr unsigned kAttribColor = 3;
constexpr unsigned kAttribAngle = 4;
constexpr unsigned kAttribStretch = 5;

// The quad spans the camera's right and up axes (a true billboard: every
// particle faces the same way, so nothing twists near the screen's edge).
const char* const kVertex = R"glsl(
#version 330 core
layout(location = 0) in vec2 aCorner;     // -1..1
layout(location = 1) in vec3 iPosition;
layout(location = 2) in float iSize;
layout(location = 3) in vec4 iColor;
layout(location = 4) in float iAngle;
layout(location = 5) in vec3 iStretch;   // world vector; zero: round

uniform mat4 uViewProjection;
uniform vec3 uRight;
uniform vec3 uUp;

out vec2 vCorner;
out vec4 vColor;

void main() {
  // Round: the quad turned by iAngle. Streak: its long side along the
  // stretch vector as seen on screen, lengthened by that vector.
  vec2 along = vec2(dot(iStretch, uRight), dot(iStretch, uUp));
  float len = length(along);
  vec2 k;
  if (len > 1e-5) {
    vec2 a = along / len;
    vec2 across = vec2(-a.y, a.x);
    k = across * (aCorner.x * 0.5 * iSize) + a * (aCorner.y * 0.5 * (iSize + len));
  } else {
    float c = cos(iAngle), s = sin(iAngle);
    k = vec2(c * aCorner.x - s * aCorner.y, s * aCorner.x + c * aCorner.y) * (0.5 * iSize);
  }
  vec3 world = iPosition + uRight * k.x + uUp * k.y;
  vCorner = aCorner;
  vColor = iColor;
  gl_Position = uViewProjection * vec4(world, 1.0);
}
)glsl";

// A soft round sprite: full at the centre, fading smoothly to nothing at the
// rim. Output is display-encoded like the other passes (shaders.h).
const char* const kFragment = R"glsl(
#version 330 core
in vec2 vCorner;
in vec4 vColor;
out vec4 fragColor;

void main() {
  float r2 = dot(vCorner, vCorner);
  if (r2 >= 1.0) discard;
  float soft = (1.0 - r2);
  soft *= soft;
  fragColor = vec4(pow(max(vColor.rgb, vec3(0.0)), vec3(1.0 / 2.2)), vColor.a * soft);
}
)glsl";

}  // namespace

void ParticlesPass::sortBackToFront(const std::vector<DrawParticle>& particles, const Eigen::Vector3f& eye,
                                    const Eigen::Vector3f& forward, std::vector<std::uint32_t>& order,
                                    std::vector<float>& depth) {
  order.resize(particles.size());
  std::iota(order.begin(), order.end(), 0u);
  depth.resize(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) depth[i] = (particles[i].position - eye).dot(forward);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return depth[a] != depth[b] ? depth[a] > depth[b] : a < b;  // ties: stable, so frames do not flicker
  });
}

Status ParticlesPass::init() {
  auto program = buildProgram("particle shader", kVertex, kFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_viewProjection = uniformLocation(m_program, "uViewProjection");
  m_right = uniformLocation(m_program, "uRight");
  m_up = uniformLocation(m_program, "uUp");
  m_vao = makeVertexArray();
  m_corners = makeBuffer();
  m_instances = makeBuffer();
  glBindVertexArray(m_vao.get());
  const float corners[8] = {-1, -1, 1, -1, -1, 1, 1, 1};  // a triangle strip
  glBindBuffer(GL_ARRAY_BUFFER, m_corners.get());
  glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  glEnableVertexAttribArray(kAttribCorner);
  glVertexAttribPointer(kAttribCorner, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, m_instances.get());
  auto instanced = [](unsigned loc, int n, std::size_t offset) {
    glEnableVertexAttribArray(loc);
    glVertexAttribPointer(loc, n, GL_FLOAT, GL_FALSE, sizeof(Instance), reinterpret_cast<const void*>(offset));
    glVertexAttribDivisor(loc, 1);
  };
  instanced(kAttribPosition, 3, offsetof(Instance, position));
  instanced(kAttribSize, 1, offsetof(Instance, size));
  instanced(kAttribColor, 4, offsetof(Instance, color));
  instanced(kAttribAngle, 1, offsetof(Instance, angle));
  instanced(kAttribStretch, 3, offsetof(Instance, stretch));
  glBindVertexArray(0);
  if (std::string errors = drainGlErrors(); !errors.empty())
    return makeError("particle pass set-up: " + errors);
  return Ok{};
}

void ParticlesPass::upload(const std::vector<DrawParticle>& particles, const std::vector<std::uint32_t>* order) {
  m_scratch.resize(particles.size());
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const DrawParticle& p = particles[order ? (*order)[k] : k];
    m_scratch[k] = {{p.position.x(), p.position.y(), p.position.z()},
                    p.size_m,
                    {p.color.x(), p.color.y(), p.color.z(), p.color.w()},
                    p.angle_rad,
                    {p.stretch_m.x(), p.stretch_m.y(), p.stretch_m.z()}};
  }
  glBindBuffer(GL_ARRAY_BUFFER, m_instances.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_scratch.size() * sizeof(Instance)), m_scratch.data(),
               GL_STREAM_DRAW);
}

Status ParticlesPass::draw(const std::vector<DrawParticle>& alphaBlended, const std::vector<DrawParticle>& additive,
                           const FrameView& view) {
  if (alphaBlended.empty() && additive.empty()) return Ok{};
  if (!created())
    if (Status s = init(); !s) return s;
  glUseProgram(m_program.get());
  glUniformMatrix4fv(m_viewProjection, 1, GL_FALSE, view.viewProjection.data());
  glUniform3fv(m_right, 1, view.right.data());
  glUniform3fv(m_up, 1, view.up.data());
  glBindVertexArray(m_vao.get());
  glEnable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  if (!alphaBlended.empty()) {
    sortBackToFront(alphaBlended, view.eye, view.forward, m_order, m_depth);
    upload(alphaBlended, &m_order);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(alphaBlended.size()));
  }
  if (!additive.empty()) {
    upload(additive, nullptr);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE, GL_ZERO, GL_ONE);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(additive.size()));
  }
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
  return Ok{};
}

}  // namespace tumble::render
