#include "render/internal/shadow_maps.h"

#include <algorithm>
#include <cmath>

namespace tumble::render {

namespace {

// Blend of logarithmic (1) and uniform (0) split distances.
constexpr float kSplitBlend = 0.75f;

}  // namespace

ShadowCascades fitShadowCascades(const FrameView& view, const Eigen::Vector3f& towardsLight, int count,
                                 float maxDistance_m, int mapSize, float casterReach_m) {
  ShadowCascades out;
  out.count = std::clamp(count, 1, kMaxShadowCascades);
  const float nearest = kNearPlane_m;
  const float farthest = std::max(maxDistance_m, 2.0f * nearest);
  const Eigen::Vector3f lz = towardsLight.normalized();
  const Eigen::Vector3f reference = std::abs(lz.y()) > 0.99f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY();
  const Eigen::Vector3f lx = reference.cross(lz).normalized();
  const Eigen::Vector3f ly = lz.cross(lx);
  float start = nearest;
  for (int i = 0; i < out.count; ++i) {
    const float f = float(i + 1) / float(out.count);
    const float end = kSplitBlend * nearest * std::pow(farthest / nearest, f) +
                      (1.0f - kSplitBlend) * (nearest + (farthest - nearest) * f);
    // Bounding sphere of the slice's eight corners: centred at their mean;
    // its radius depends only on the slice and the field of view, so the
    // map's world size stays fixed while the camera turns.
    Eigen::Vector3f corners[8];
    Eigen::Vector3f centre = Eigen::Vector3f::Zero();
    int k = 0;
    for (float d : {start, end})
      for (float sx : {-1.0f, 1.0f})
        for (float sy : {-1.0f, 1.0f}) {
          corners[k] = view.eye + d * (view.forward + sx * view.tanHalfFovX * view.right + sy * view.tanHalfFovY * view.up);
          centre += corners[k++];
        }
    centre /= 8.0f;
    float radius = 0;
    for (const Eigen::Vector3f& c : corners) radius = std::max(radius, (c - centre).norm());
    radius = std::ceil(radius * 16.0f) / 16.0f;
    const float texel = 2.0f * radius / float(std::max(mapSize, 1));
    // Snap the centre to whole texels of a light-space lattice fixed in the
    // world, so moving the camera moves the map by whole texels only.
    const float cx = std::floor(lx.dot(centre) / texel) * texel;
    const float cy = std::floor(ly.dot(centre) / texel) * texel;
    const float cz = lz.dot(centre);
    const float zMin = cz - radius, zMax = cz + radius + casterReach_m;
    Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
    m.block<1, 3>(0, 0) = lx.transpose() / radius;
    m(0, 3) = -cx / radius;
    m.block<1, 3>(1, 0) = ly.transpose() / radius;
    m(1, 3) = -cy / radius;
    m.block<1, 3>(2, 0) = -2.0f * lz.transpose() / (zMax - zMin);
    m(2, 3) = (zMax + zMin) / (zMax - zMin);
    m(3, 3) = 1.0f;
    out.lightViewProjection[i] = m;
    out.far_m[i] = end;
    out.texel_m[i] = texel;
    start = end;
  }
  return out;
}

Status ShadowMaps::resize(int mapSize, int cascades) {
  mapSize = std::clamp(mapSize, 64, 4096);
  cascades = std::clamp(cascades, 1, kMaxShadowCascades);
  if (mapSize == m_size && cascades == m_cascades && m_texture.get() != 0) return Ok{};
  m_size = mapSize;
  m_cascades = cascades;
  m_texture = makeTexture();
  glBindTexture(GL_TEXTURE_2D_ARRAY, m_texture.get());
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT24, mapSize, mapSize, cascades, 0, GL_DEPTH_COMPONENT,
               GL_UNSIGNED_INT, nullptr);
  // Linear filtering of a comparison gives bilinear PCF for free.
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  m_framebuffer = makeFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.get());
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m_texture.get(), 0, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    m_texture.reset();
    return makeError("shadow maps: depth framebuffer incomplete (status " + std::to_string(status) + ")");
  }
  return Ok{};
}

void ShadowMaps::bindCascade(int i) const {
  glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.get());
  glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, m_texture.get(), 0, i);
  glViewport(0, 0, m_size, m_size);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);
  glDisable(GL_CULL_FACE);
}

void ShadowMaps::finish() const {
  glDisable(GL_POLYGON_OFFSET_FILL);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace tumble::render
