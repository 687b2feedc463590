#pragma once
// Particle billboards (runtime/render/particles_pass.cpp): instanced
// camera-facing quads with a soft round sprite computed in the fragment
// shader (no texture). Alpha-blended particles are sorted back to front and
// drawn first, additive ones after; both depth-tested against the scene
// without writing depth, so they hide behind shapes but not each other.
// GL objects are created on the first frame that has particles.
#include <cstdint>
#include <vector>

#include "core/result.h"
#include "render/internal/camera_math.h"
#include "render/internal/gl_util.h"
#include "render/renderer.h"

namespace tumble::render {

class ParticlesPass {
 public:
  /// Draws both lists; does nothing (and creates nothing) when both are empty.
  Status draw(const std::vector<DrawParticle>& alphaBlended, const std::vector<DrawParticle>& additive,
              const FrameView& view);
  bool created() const { return m_program.get() != 0; }

  /// Indices of `particles` sorted by distance along `forward` from `eye`,
  /// farthest first (the back-to-front order alpha blending needs). `depth`
  /// is scratch space (kept between frames, so no allocation per frame).
  static void sortBackToFront(const std::vector<DrawParticle>& particles, const Eigen::Vector3f& eye,
                              const Eigen::Vector3f& forward, std::vector<std::uint32_t>& order,
                              std::vector<float>& depth);

 private:
  struct Instance {
    float position[3];
    float size;
    float color[4];
    float angle;
    float stretch[3];
  };
  Status init();
  void upload(const std::vector<DrawParticle>& particles, const std::vector<std::uint32_t>* order);

  GlProgram m_program;
  GlVertexArray m_vao;
  GlBuffer m_corners, m_instances;
  GLint m_viewProjection = -1, m_right = -1, m_up = -1;
  std::vector<Instance> m_scratch;
  std::vector<std::uint32_t> m_order;
  std::vector<float> m_depth;
};

}  // namespace tumble::render
