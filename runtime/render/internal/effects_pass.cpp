#include "render/internal/effects_pass.h"

#include <algorithm>
#include <cmath>

#include "render/internal/shaders.h"

namespace tumble::render {

namespace {

constexpr int kSpriteSize = 64;
constexpr int kSpriteCount = 4;  // glow, ring, hexagon, streak
constexpr float kSunDistance_m = 1500.0f;     // inside the far plane, behind any drawn scenery
constexpr float kSunQuadHalf_rad = 0.012f;    // the tested patch: a little larger than the disc

float smoothstep(float a, float b, float x) {
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// One flare element: its place on the line from the sun (0) through the
// screen centre (0.5) to the mirrored point (1), radius as a fraction of the
// screen height, sprite and tint.
struct FlareElement {
  float along, radius;
  int sprite;
  float r, g, b, strength;
};
constexpr FlareElement kFlare[] = {
    {0.00f, 0.30f, 0, 1.00f, 0.95f, 0.85f, 0.55f},  // glow around the sun
    {0.00f, 0.45f, 3, 1.00f, 0.90f, 0.80f, 0.30f},  // horizontal streak
    {0.22f, 0.05f, 2, 0.60f, 0.80f, 1.00f, 0.25f},
    {0.38f, 0.09f, 1, 1.00f, 0.70f, 0.40f, 0.22f},
    {0.55f, 0.03f, 2, 0.70f, 1.00f, 0.70f, 0.30f},
    {0.72f, 0.12f, 2, 0.50f, 0.60f, 1.00f, 0.15f},
    {0.90f, 0.20f, 1, 0.80f, 0.60f, 1.00f, 0.12f},
};

void pushVertex(std::vector<float>& v, const Eigen::Vector3f& p, float u, float w, const Eigen::Vector4f& c) {
  v.insert(v.end(), {p.x(), p.y(), p.z(), u, w, c.x(), c.y(), c.z(), c.w()});
}

// Two triangles: corners a0 a1 b1 b0, uv per corner.
void pushQuad(std::vector<float>& v, const Eigen::Vector3f* corners, const Eigen::Vector2f* uvs,
              const Eigen::Vector4f& color) {
  for (int i : {0, 1, 2, 0, 2, 3}) pushVertex(v, corners[i], uvs[i].x(), uvs[i].y(), color);
}

}  // namespace

std::vector<std::uint8_t> buildFlareSprites(int size, int count) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(size) * size * count, 0);
  for (int s = 0; s < count; ++s)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const float u = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
        const float v = 2.0f * (float(y) + 0.5f) / float(size) - 1.0f;
        const float r = std::sqrt(u * u + v * v);
        float a = 0;
        switch (s % 4) {
          case 0: a = std::pow(std::max(0.0f, 1.0f - r), 2.5f); break;                           // glow
          case 1: a = std::exp(-std::pow((r - 0.8f) / 0.06f, 2.0f)) * (r < 1.0f ? 1.0f : 0.0f); break;  // ring
          case 2: {  // hexagon, soft edged: distance to the nearest of three edge pairs
            const float au = std::abs(u), av = std::abs(v);
            const float hex = std::max(au * 0.866f + av * 0.5f, av);
            a = 0.6f * (1.0f - smoothstep(0.7f, 0.8f, hex)) + 0.4f * std::exp(-std::pow((hex - 0.75f) / 0.05f, 2.0f));
            break;
          }
          default: a = std::exp(-std::pow(v / 0.04f, 2.0f)) * std::max(0.0f, 1.0f - std::abs(u)); break;  // streak
        }
        out[(static_cast<std::size_t>(y) * size * count) + static_cast<std::size_t>(s) * size + x] =
            static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(a, 0.0f, 1.0f)));
      }
  return out;
}

Status EffectsPass::init() {
  m_initialised = true;
  auto program = buildProgram("effects shader", shaders::kEffectsVertex, shaders::kEffectsFragment);
  if (!program) return makeError(program.error());
  m_program = std::move(*program);
  m_viewProjection = uniformLocation(m_program, "uViewProjection");
  m_texture = uniformLocation(m_program, "uSprites");
  m_useTexture = uniformLocation(m_program, "uUseTexture");
  m_vao = makeVertexArray();
  m_vertices = makeBuffer();
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_vertices.get());
  const GLsizei stride = 9 * sizeof(float);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(5 * sizeof(float)));
  glBindVertexArray(0);
  const std::vector<std::uint8_t> sprites = buildFlareSprites(kSpriteSize, kSpriteCount);
  m_sprites = makeTexture();
  glBindTexture(GL_TEXTURE_2D, m_sprites.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, kSpriteSize * kSpriteCount, kSpriteSize, 0, GL_RED, GL_UNSIGNED_BYTE,
               sprites.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  glGenQueries(1, &m_query);
  return Ok{};
}

EffectsPass::~EffectsPass() {
  if (m_query != 0) glDeleteQueries(1, &m_query);
}

Status EffectsPass::drawLightning(const std::vector<Eigen::Vector3f>& segments, float brightness,
                                  const FrameView& view) {
  if (segments.size() < 2 || brightness <= 0.0f) return Ok{};
  if (!m_initialised) {
    if (Status s = init(); !s) return s;
  }
  if (!m_program.get()) return Ok{};
  m_scratch.clear();
  // A wide dim glow and a narrow white core per segment, facing the eye.
  const struct {
    float halfWidth_m;
    Eigen::Vector4f color;
  } strips[] = {{7.0f, {0.45f, 0.5f, 1.0f, 0.35f * brightness}}, {1.3f, {1.0f, 1.0f, 1.0f, brightness}}};
  const Eigen::Vector2f uvs[4] = {{0, -1}, {0, 1}, {0, 1}, {0, -1}};
  for (const auto& strip : strips)
    for (std::size_t i = 0; i + 1 < segments.size(); i += 2) {
      const Eigen::Vector3f a = segments[i], b = segments[i + 1];
      Eigen::Vector3f side = (b - a).cross(view.eye - a);
      if (side.squaredNorm() < 1e-12f) continue;
      side = side.normalized() * strip.halfWidth_m;
      const Eigen::Vector3f corners[4] = {a - side, a + side, b + side, b - side};
      pushQuad(m_scratch, corners, uvs, strip.color);
    }
  glUseProgram(m_program.get());
  glUniformMatrix4fv(m_viewProjection, 1, GL_FALSE, view.viewProjection.data());
  glUniform1i(m_useTexture, 0);
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_vertices.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_scratch.size() * sizeof(float)), m_scratch.data(),
               GL_STREAM_DRAW);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_scratch.size() / 9));
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  return Ok{};
}

Result<float> EffectsPass::drawFlare(const FrameView& view, const Environment& environment) {
  const Eigen::Vector3f& sun = environment.lightDirection;
  const float brightness = environment.sunDisc * std::clamp(environment.lightColor.maxCoeff(), 0.0f, 1.0f);
  if (brightness <= 0.02f || sun.dot(view.forward) <= 0.0f) return 0.0f;
  const Eigen::Vector4f clip = view.viewProjection * (view.eye + kSunDistance_m * sun).homogeneous();
  if (clip.w() <= 0.0f) return 0.0f;
  const Eigen::Vector2f screen(clip.x() / clip.w(), clip.y() / clip.w());
  if (screen.cwiseAbs().maxCoeff() > 1.3f) return 0.0f;
  if (!m_initialised) {
    if (Status s = init(); !s) return makeError(s.error());
  }
  if (!m_program.get()) return 0.0f;

  // The depth test: a patch of sky around the sun drawn at 1.5 km, once
  // against the scene's depth and once regardless; the ratio of samples
  // that passed is the uncovered part of the sun.
  m_scratch.clear();
  const Eigen::Vector3f centre = view.eye + kSunDistance_m * sun;
  const Eigen::Vector3f reference = std::abs(sun.y()) > 0.99f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  const Eigen::Vector3f ax = reference.cross(sun).normalized() * (kSunDistance_m * kSunQuadHalf_rad);
  const Eigen::Vector3f ay = sun.cross(ax);
  const Eigen::Vector3f patch[4] = {centre - ax - ay, centre + ax - ay, centre + ax + ay, centre - ax + ay};
  const Eigen::Vector2f none[4] = {{0, 0}, {0, 0}, {0, 0}, {0, 0}};
  pushQuad(m_scratch, patch, none, Eigen::Vector4f::Zero());
  glUseProgram(m_program.get());
  glUniformMatrix4fv(m_viewProjection, 1, GL_FALSE, view.viewProjection.data());
  glUniform1i(m_useTexture, 0);
  glBindVertexArray(m_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m_vertices.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_scratch.size() * sizeof(float)), m_scratch.data(),
               GL_STREAM_DRAW);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_FALSE);
  glEnable(GL_DEPTH_TEST);
  GLuint passed = 0, total = 0;
  for (GLenum func : {GLenum(GL_LEQUAL), GLenum(GL_ALWAYS)}) {
    glDepthFunc(func);
    glBeginQuery(GL_SAMPLES_PASSED, m_query);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glEndQuery(GL_SAMPLES_PASSED);
    // Read at once: a software rasteriser has finished anyway, and a
    // one-frame screenshot needs this frame's answer.
    glGetQueryObjectuiv(m_query, GL_QUERY_RESULT, func == GL_LEQUAL ? &passed : &total);
  }
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glDepthFunc(GL_LESS);
  if (total == 0) {
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    return 0.0f;
  }
  const float visible = std::clamp(float(passed) / float(total), 0.0f, 1.0f);
  const float edge = 1.0f - smoothstep(0.8f, 1.3f, screen.cwiseAbs().maxCoeff());
  const float strength = visible * brightness * edge;
  if (strength > 0.003f) {
    m_scratch.clear();
    const float aspect = view.tanHalfFovX / view.tanHalfFovY;
    for (const FlareElement& f : kFlare) {
      const Eigen::Vector2f p = screen * (1.0f - 2.0f * f.along);
      const float rx = f.radius / aspect * 2.0f, ry = f.radius * 2.0f;
      const Eigen::Vector3f corners[4] = {{p.x() - rx, p.y() - ry, 0}, {p.x() + rx, p.y() - ry, 0},
                                          {p.x() + rx, p.y() + ry, 0}, {p.x() - rx, p.y() + ry, 0}};
      const float u0 = float(f.sprite) / kSpriteCount, u1 = float(f.sprite + 1) / kSpriteCount;
      const Eigen::Vector2f uvs[4] = {{u0, 0}, {u1, 0}, {u1, 1}, {u0, 1}};
      pushQuad(m_scratch, corners, uvs, Eigen::Vector4f(f.r, f.g, f.b, f.strength * strength));
    }
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(m_scratch.size() * sizeof(float)), m_scratch.data(),
                 GL_STREAM_DRAW);
    glUniformMatrix4fv(m_viewProjection, 1, GL_FALSE, Eigen::Matrix4f::Identity().eval().data());
    glUniform1i(m_useTexture, 1);
    glUniform1i(m_texture, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, m_sprites.get());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(m_scratch.size() / 9));
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
  return visible;
}

}  // namespace tumble::render
