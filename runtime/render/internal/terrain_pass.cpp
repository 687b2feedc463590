#include "render/internal/terrain_pass.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "core/log.h"
#include "core/process_stats.h"
#include "render/internal/shaders.h"
#include "render/internal/terrain_textures.h"

namespace tumble::render {

namespace {
// Adds the wall time from its construction to its destruction to a stats field, ms.
class AddElapsed {
 public:
  explicit AddElapsed(double& total_ms) : m_total(total_ms) {}
  ~AddElapsed() { m_total += 1000.0 * m_clock.seconds(); }
  AddElapsed(const AddElapsed&) = delete;
  AddElapsed& operator=(const AddElapsed&) = delete;

 private:
  double& m_total;
  Stopwatch m_clock;
};

// Fog reaches 1 - exp(-(d rho)^2); beyond d rho = 2.5 it is within half a
// step of 8-bit colour of the fog colour, so such chunks are not drawn.
constexpr float kFogCutoff = 2.5f;
// Strength of the bump detail at bump = 255: the noise gradient is scaled so
// the shading normal tilts by up to about 40 degrees on the roughest rock.
constexpr float kDetailSlope = 0.4f;

int verticesAlong(int blocks, int lod) {
  const int step = 1 << lod;
  return (blocks + step - 1) / step + 1;
}

}  // namespace

Result<TerrainPass::Program> TerrainPass::buildTerrainProgram(const char* name, const char* vertex,
                                                             const char* fragment) {
  auto built = buildProgram(name, vertex, fragment);
  if (!built) return makeError(built.error());
  Program p;
  p.program = std::move(*built);
  p.lit.locate(p.program);
  p.origin = uniformLocation(p.program, "uOrigin");
  p.spacing = uniformLocation(p.program, "uSpacing");
  p.blocks = uniformLocation(p.program, "uBlocks");
  p.texturePerMetre = uniformLocation(p.program, "uTexturePerMetre");
  p.layerCount = uniformLocation(p.program, "uLayerCount");
  p.detailSlope = uniformLocation(p.program, "uDetailSlope");
  p.blend = uniformLocation(p.program, "uBlend");
  glUseProgram(p.program.get());
  glUniform1i(uniformLocation(p.program, "uMaterial"), 0);
  glUniform1i(uniformLocation(p.program, "uTextures"), 1);
  return p;
}

GlTexture makeGroundTextureArray() {
  GlTexture textures = makeTexture();
  glBindTexture(GL_TEXTURE_2D_ARRAY, textures.get());
  glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_SRGB8_ALPHA8, kTerrainTextureSize, kTerrainTextureSize,
               kTerrainTextureCount, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  for (int layer = 0; layer < kTerrainTextureCount; ++layer) {
    const std::vector<std::uint8_t> rgba = generateTerrainTexture(layer);
    glTexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, kTerrainTextureSize, kTerrainTextureSize, 1,
                    GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  }
  glGenerateMipmap(GL_TEXTURE_2D_ARRAY);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_NEAREST);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_REPEAT);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  return textures;
}

Status TerrainPass::init() {
  const auto start = std::chrono::steady_clock::now();
  auto detailed = buildTerrainProgram("terrain shader", shaders::kTerrainVertex, shaders::kTerrainFragment);
  if (!detailed) return makeError(detailed.error());
  m_detailed = std::move(*detailed);
  auto simple = buildTerrainProgram("terrain shader (per vertex light)", shaders::kTerrainVertexLit,
                                    shaders::kTerrainFragmentLit);
  if (!simple) return makeError(simple.error());
  m_simple = std::move(*simple);
  auto depth = buildProgram("terrain shadow shader", shaders::kTerrainVertex, shaders::kDepthFragment);
  if (!depth) return makeError(depth.error());
  m_depthProgram = std::move(*depth);
  m_depthViewProjection = uniformLocation(m_depthProgram, "uViewProjection");

  // Material textures, generated here (first terrain frame), not at start-up:
  // a scene without terrain never pays for them.
  m_textures = makeGroundTextureArray();

  m_materials = makeTexture();
  if (std::string errors = drainGlErrors(); !errors.empty()) {
    return makeError("terrain pass set-up: " + errors);
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  log::info("render: terrain textures generated (" + std::to_string(kTerrainTextureCount) + " x " +
            std::to_string(kTerrainTextureSize) + "^2) in " + std::to_string(static_cast<int>(ms)) + " ms");
  m_initialised = true;
  return Ok{};
}

void TerrainPass::reset(const TerrainSurface& surface) {
  m_chunks.clear();  // frees every chunk's vertex buffers
  m_residentBytes = 0;
  m_grid = chunkGrid(surface);
  m_chunks.resize(static_cast<std::size_t>(m_grid.chunksX) * static_cast<std::size_t>(m_grid.chunksZ));
  for (int cz = 0; cz < m_grid.chunksZ; ++cz) {
    for (int cx = 0; cx < m_grid.chunksX; ++cx) {
      m_chunks[static_cast<std::size_t>(cz * m_grid.chunksX + cx)].bounds = chunkBounds(surface, cx, cz);
    }
  }
  uploadMaterials(surface);
}

void TerrainPass::uploadMaterials(const TerrainSurface& surface) {
  // Interleave texture index and bump into RG; a missing layer reads 0.
  const std::size_t blocks = static_cast<std::size_t>(m_grid.blocksX) * static_cast<std::size_t>(m_grid.blocksZ);
  m_materialScratch.assign(blocks * 2, 0);
  for (std::size_t b = 0; b < blocks; ++b) {
    if (surface.textureIndex != nullptr) m_materialScratch[2 * b] = surface.textureIndex[b];
    if (surface.bump != nullptr) m_materialScratch[2 * b + 1] = surface.bump[b];
  }
  glBindTexture(GL_TEXTURE_2D, m_materials.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 2 * blocksX bytes
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RG8UI, m_grid.blocksX, m_grid.blocksZ, 0, GL_RG_INTEGER,
               GL_UNSIGNED_BYTE, m_materialScratch.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glBindTexture(GL_TEXTURE_2D, 0);
  m_materialScratch.clear();
  m_materialScratch.shrink_to_fit();  // 32 MiB on a 4097^2 map: do not keep it
}

void TerrainPass::updateDirty(const TerrainSurface& surface, TerrainStats& stats) {
  // A vertex's normal reads its neighbours (central differences), so the
  // samples one around the rectangle change too.
  const int i0 = std::max(surface.dirtyI0 - 1, 0), j0 = std::max(surface.dirtyJ0 - 1, 0);
  const int i1 = std::min(surface.dirtyI1 + 1, m_grid.blocksX), j1 = std::min(surface.dirtyJ1 + 1, m_grid.blocksZ);
  if (i0 > i1 || j0 > j1) return;
  // Chunk cx holds samples cx * 64 .. cx * 64 + 64 (its neighbour shares the edge).
  const auto firstChunk = [](int sample) { return std::max(0, (sample - 1) / kTerrainChunkBlocks); };
  const int cx0 = firstChunk(i0), cz0 = firstChunk(j0);
  const int cx1 = std::min(i1 / kTerrainChunkBlocks, m_grid.chunksX - 1);
  const int cz1 = std::min(j1 / kTerrainChunkBlocks, m_grid.chunksZ - 1);
  for (int cz = cz0; cz <= cz1; ++cz) {
    for (int cx = cx0; cx <= cx1; ++cx) {
      Chunk& chunk = m_chunks[static_cast<std::size_t>(cz * m_grid.chunksX + cx)];
      for (ChunkLevel& level : chunk.levels) {
        m_residentBytes -= level.bytes;
        level = ChunkLevel{};
      }
      chunk.bounds = chunkBounds(surface, cx, cz);
      ++stats.chunksInvalidated;
    }
  }
  // Blocks i - 1 and i hold sample i.
  uploadMaterialRect(surface, std::max(surface.dirtyI0 - 1, 0), std::max(surface.dirtyJ0 - 1, 0),
                     std::min(surface.dirtyI1, m_grid.blocksX - 1), std::min(surface.dirtyJ1, m_grid.blocksZ - 1));
  stats.materialsUploaded = true;
}

void TerrainPass::uploadMaterialRect(const TerrainSurface& surface, int bi0, int bj0, int bi1, int bj1) {
  if (bi0 > bi1 || bj0 > bj1) return;
  const int w = bi1 - bi0 + 1, h = bj1 - bj0 + 1;
  m_materialScratch.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 2, 0);
  for (int bj = bj0; bj <= bj1; ++bj) {
    for (int bi = bi0; bi <= bi1; ++bi) {
      const std::size_t b = static_cast<std::size_t>(bj) * static_cast<std::size_t>(m_grid.blocksX) +
                            static_cast<std::size_t>(bi);
      const std::size_t o = 2 * (static_cast<std::size_t>(bj - bj0) * static_cast<std::size_t>(w) +
                                 static_cast<std::size_t>(bi - bi0));
      if (surface.textureIndex != nullptr) m_materialScratch[o] = surface.textureIndex[b];
      if (surface.bump != nullptr) m_materialScratch[o + 1] = surface.bump[b];
    }
  }
  glBindTexture(GL_TEXTURE_2D, m_materials.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexSubImage2D(GL_TEXTURE_2D, 0, bi0, bj0, w, h, GL_RG_INTEGER, GL_UNSIGNED_BYTE, m_materialScratch.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glBindTexture(GL_TEXTURE_2D, 0);
  m_materialScratch.clear();
}

const TerrainPass::IndexSet& TerrainPass::indexSet(int nx, int nz) {
  for (const IndexSet& set : m_indexSets) {
    if (set.nx == nx && set.nz == nz) return set;
  }
  const std::vector<std::uint16_t> indices = buildChunkIndices(nx, nz);
  IndexSet set;
  set.nx = nx;
  set.nz = nz;
  set.count = static_cast<int>(indices.size());
  set.buffer = makeBuffer();
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, set.buffer.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint16_t)),
               indices.data(), GL_STATIC_DRAW);
  m_indexSets.push_back(std::move(set));
  return m_indexSets.back();
}

TerrainPass::ChunkLevel& TerrainPass::ensureLevel(const TerrainSurface& surface, int chunk, int lod,
                                                  TerrainStats& stats) {
  ChunkLevel& level = m_chunks[static_cast<std::size_t>(chunk)].levels[static_cast<std::size_t>(lod)];
  level.lastUsedFrame = m_frame;
  if (level.vao.get() != 0) return level;

  const AddElapsed timed(stats.updateTime_ms);
  const int cx = chunk % m_grid.chunksX, cz = chunk / m_grid.chunksX;
  const int nx = verticesAlong(std::min(kTerrainChunkBlocks, m_grid.blocksX - cx * kTerrainChunkBlocks), lod);
  const int nz = verticesAlong(std::min(kTerrainChunkBlocks, m_grid.blocksZ - cz * kTerrainChunkBlocks), lod);
  buildChunkVertices(surface, cx, cz, lod, m_scratch);

  level.vao = makeVertexArray();
  level.vertices = makeBuffer();
  glBindVertexArray(level.vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, level.vertices.get());
  level.bytes = m_scratch.size() * sizeof(TerrainVertex);
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(level.bytes), m_scratch.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(shaders::kAttribTerrainPosition);
  glVertexAttribPointer(shaders::kAttribTerrainPosition, 3, GL_FLOAT, GL_FALSE, sizeof(TerrainVertex),
                        reinterpret_cast<const void*>(offsetof(TerrainVertex, position)));
  glEnableVertexAttribArray(shaders::kAttribTerrainNormal);
  glVertexAttribPointer(shaders::kAttribTerrainNormal, 4, GL_INT_2_10_10_10_REV, GL_TRUE,
                        sizeof(TerrainVertex), reinterpret_cast<const void*>(offsetof(TerrainVertex, normal)));
  const IndexSet& indices = indexSet(nx, nz);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.buffer.get());  // recorded in the VAO
  glBindVertexArray(0);
  level.triangles = indices.count / 3;
  m_residentBytes += level.bytes;
  ++stats.chunksUploaded;
  return level;
}

void TerrainPass::evictUnused() {
  if (m_residentBytes <= kTerrainResidentBudget) return;
  for (Chunk& chunk : m_chunks) {
    for (ChunkLevel& level : chunk.levels) {
      if (level.vao.get() != 0 && level.lastUsedFrame != m_frame) {
        m_residentBytes -= level.bytes;
        level = ChunkLevel{};
      }
    }
  }
}

Status TerrainPass::sync(const TerrainSurface& surface, TerrainStats& stats) {
  if (!m_initialised) {
    if (Status s = init(); !s) return s;
  }
  const SurfaceKey key{surface.samplesX,   surface.samplesZ,  surface.spacing_m, surface.heightScale_m,
                       surface.baseHeight_m, surface.originX_m, surface.originZ_m, surface.heights,
                       surface.textureIndex, surface.bump,     surface.revision};
  SurfaceKey sameRevision = key;
  sameRevision.revision = m_key.revision;
  const bool onlyDirty = m_hasSurface && sameRevision == m_key && key.revision != m_key.revision &&
                         surface.dirtySinceRevision == m_key.revision && surface.dirtyI0 <= surface.dirtyI1 &&
                         surface.dirtyJ0 <= surface.dirtyJ1;
  const AddElapsed timed(stats.updateTime_ms);
  if (onlyDirty) {
    updateDirty(surface, stats);
    m_key = key;
  } else if (!m_hasSurface || !(key == m_key)) {
    reset(surface);
    m_key = key;
    m_hasSurface = true;
    stats.materialsUploaded = true;
  }
  return Ok{};
}

Status TerrainPass::drawDepth(const TerrainSurface& surface, const Eigen::Matrix4f& lightViewProjection,
                              const Eigen::Vector3f& eye, float pixelsPerRadian, float lodPixels) {
  if (chunkGrid(surface).chunksX == 0) return Ok{};
  // Uploads made here are reported by this frame's draw (m_depthUploads).
  TerrainStats& uploads = m_depthUploads;
  if (Status s = sync(surface, uploads); !s) return s;
  const FrustumPlanes planes = frustumPlanes(lightViewProjection);
  glUseProgram(m_depthProgram.get());
  glUniformMatrix4fv(m_depthViewProjection, 1, GL_FALSE, lightViewProjection.data());
  for (int c = 0; c < static_cast<int>(m_chunks.size()); ++c) {
    const ChunkBounds& bounds = m_chunks[static_cast<std::size_t>(c)].bounds;
    if (!boxInFrustum(planes, bounds)) continue;
    const int lod = chooseLod(distanceToBox(eye, bounds), surface.spacing_m, pixelsPerRadian, lodPixels);
    const ChunkLevel& level = ensureLevel(surface, c, lod, uploads);
    glBindVertexArray(level.vao.get());
    glDrawElements(GL_TRIANGLES, level.triangles * 3, GL_UNSIGNED_SHORT, nullptr);
  }
  glBindVertexArray(0);
  return Ok{};
}

Status TerrainPass::draw(const TerrainSurface& surface, const FrameView& view,
                         const Environment& environment, float pixelsPerRadian, float lodPixels, bool detail,
                         bool blend,
                         TerrainStats& stats) {
  std::vector<TerrainChunkDraw> drawn = std::move(stats.drawn);  // keep its capacity
  drawn.clear();
  stats = TerrainStats{};
  stats.drawn = std::move(drawn);
  if (chunkGrid(surface).chunksX == 0) return Ok{};
  if (Status s = sync(surface, stats); !s) return s;
  stats.materialsUploaded = stats.materialsUploaded || m_depthUploads.materialsUploaded;
  stats.chunksUploaded += m_depthUploads.chunksUploaded;
  stats.chunksInvalidated += m_depthUploads.chunksInvalidated;
  stats.updateTime_ms += m_depthUploads.updateTime_ms;
  m_depthUploads = TerrainStats{};
  ++m_frame;

  // Cull and choose levels.
  const FrustumPlanes planes = frustumPlanes(view.viewProjection);
  const float fogLimit_m = environment.fogDensity_per_m > 0 ? kFogCutoff / environment.fogDensity_per_m
                                                            : std::numeric_limits<float>::max();
  m_visible.clear();
  for (int c = 0; c < static_cast<int>(m_chunks.size()); ++c) {
    const ChunkBounds& bounds = m_chunks[static_cast<std::size_t>(c)].bounds;
    const float distance = distanceToBox(view.eye, bounds);
    if (distance > fogLimit_m || !boxInFrustum(planes, bounds)) continue;
    m_visible.push_back({c, chooseLod(distance, surface.spacing_m, pixelsPerRadian, lodPixels), distance});
  }
  // Front to back, so the depth test rejects hidden fragments before shading.
  std::sort(m_visible.begin(), m_visible.end(),
            [](const Visible& a, const Visible& b) { return a.distance_m < b.distance_m; });
  stats.chunksTotal = static_cast<int>(m_chunks.size());
  stats.chunksCulled = stats.chunksTotal - static_cast<int>(m_visible.size());

  const Program& p = detail ? m_detailed : m_simple;
  glUseProgram(p.program.get());
  p.lit.apply(view, environment);
  glUniform2f(p.origin, surface.originX_m, surface.originZ_m);
  glUniform1f(p.spacing, surface.spacing_m);
  glUniform2i(p.blocks, m_grid.blocksX, m_grid.blocksZ);
  glUniform1f(p.texturePerMetre, 1.0f / kTerrainTextureSize_m);
  glUniform1i(p.layerCount, kTerrainTextureCount);
  glUniform1f(p.detailSlope, kDetailSlope);
  glUniform1i(p.blend, blend ? 1 : 0);  // the detailed shader only (-1 is ignored)
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, m_materials.get());
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D_ARRAY, m_textures.get());

  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  for (const Visible& v : m_visible) {
    const ChunkLevel& level = ensureLevel(surface, v.chunk, v.lod, stats);
    glBindVertexArray(level.vao.get());
    glDrawElements(GL_TRIANGLES, level.triangles * 3, GL_UNSIGNED_SHORT, nullptr);
    stats.trianglesDrawn += level.triangles;
    stats.drawn.push_back({v.chunk % m_grid.chunksX, v.chunk / m_grid.chunksX, v.lod, level.triangles});
  }
  stats.chunksDrawn = static_cast<int>(m_visible.size());
  glBindVertexArray(0);
  glDisable(GL_CULL_FACE);
  glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, 0);

  evictUnused();
  stats.residentBytes = m_residentBytes;
  return Ok{};
}

}  // namespace tumble::render
