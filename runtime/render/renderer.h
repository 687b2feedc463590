#pragma once
// The render module: an SDL2 window (or SDL's offscreen driver with Mesa when
// there is no display), an OpenGL 3.3 core context through libepoxy, and one
// call per frame that draws what the simulation handed over.
//
// Index
//   DrawShape, DebugLine, FrameSnapshot   what the renderer reads (plain data)
//   ConvexMeshData                        a convex mesh (physics hull) drawn flat shaded
//   TerrainSurface, TerrainStats          height-field view the app fills; what was drawn
//   Camera, CameraMode                    orbit / follow camera
//   HudStats, Controls                    the Dear ImGui HUD: shown / changed
//   WindowConfig, Renderer                window, events, drawing, screenshots
//
// render is a leaf: it depends on core only. The app copies simulation state
// into a FrameSnapshot; nothing here reads physics, script or particles, and
// the simulation never reads render (ARCHITECTURE.md).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"

namespace tumble::render {

enum class ShapeKind { Box, Sphere, Capsule, Plane, ConvexMesh };

/// Vertices and triangles of a convex mesh (a physics hull) in its shape's
/// local frame. Drawn flat shaded (one normal per triangle), uploaded to the
/// GPU once per id and dropped when no shape has used it for a while.
struct ConvexMeshData {
  std::uint64_t id = 0;                    // unique per distinct mesh while the renderer lives
  std::vector<Eigen::Vector3f> vertices;   // m, local frame
  std::vector<std::uint32_t> indices;      // triangle list, counter-clockwise seen from outside
};

struct DrawShape {
  ShapeKind kind = ShapeKind::Box;
  Eigen::Vector3f position{0, 0, 0};  // m, world; for Plane: a point on the plane
  // Rotation from local to world. Plane: maps local +Y to the plane normal.
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  Eigen::Vector3f halfExtents{0.5f, 0.5f, 0.5f};  // m, Box
  float radius_m = 0.5f;                          // Sphere, Capsule
  // Capsule: half length of the core segment along local Y (caps excluded),
  // so the capsule's total height is 2 * (halfHeight_m + radius_m).
  float halfHeight_m = 0.5f;
  std::shared_ptr<const ConvexMeshData> convexMesh;  // ConvexMesh: the mesh (shared; not copied per frame)
  Eigen::Vector3f color{0.8f, 0.8f, 0.8f};  // linear RGB 0..1; Plane: colour of the light squares
  bool sleeping = false;                    // drawn a little darker
};

struct DebugLine {
  Eigen::Vector3f a, b;                     // m, world
  Eigen::Vector3f color{1, 1, 0};           // linear RGB 0..1
};

/// A plain view of a height field (render never includes terrain; the app
/// fills this from terrain::Terrain). No ownership: the arrays must stay
/// valid during each drawFrame that is handed this surface.
///
/// Sample (i, j) is at x = originX_m + i * spacing_m, z = originZ_m + j *
/// spacing_m, y = baseHeight_m + heights[j * samplesX + i] * heightScale_m.
/// Block (bi, bj) is the cell between samples (bi, bj) and (bi + 1, bj + 1),
/// cut along its p00-p11 diagonal like the collision triangles.
struct TerrainSurface {
  int samplesX = 0, samplesZ = 0;  // grid size; fewer than 2 x 2 draws nothing
  float spacing_m = 1, heightScale_m = 0.01f, baseHeight_m = 0, originX_m = 0, originZ_m = 0;
  const std::uint16_t* heights = nullptr;      // samplesX * samplesZ, row-major (j * samplesX + i)
  // Per block ((samplesX - 1) * (samplesZ - 1), row-major bj * (samplesX - 1) + bi), optional.
  // Texture: 0 grass, 1 rock, 2 sand, 3 mud, 4 snow, 5 gravel, 6 dirt, 7 moss
  // (kTerrainTextureCount; larger values wrap). Missing: grass everywhere.
  const std::uint8_t* textureIndex = nullptr;
  // Fine shading detail, 0 = smooth .. 255 = strongest. Missing: 0.
  const std::uint8_t* bump = nullptr;
  // Bump it whenever heights or materials change: the renderer then rebuilds
  // its chunk meshes (lazily, only those it draws) and re-uploads materials.
  // A change of size, spacing, scale, origin or pointers also counts.
  std::uint64_t revision = 0;
};

/// Number of built-in procedural terrain textures (see TerrainSurface).
inline constexpr int kTerrainTextureCount = 8;

/// Everything the renderer reads of the simulation.
struct FrameSnapshot {
  std::vector<DrawShape> shapes;
  std::vector<DebugLine> lines;
  double simTime_s = 0;
  const TerrainSurface* terrain = nullptr;  // optional; null: no terrain, no terrain GPU memory
};

/// What the terrain pass did in the last drawFrame (Renderer::terrainStats).
/// The map is cut into chunks of kTerrainChunkBlocks x kTerrainChunkBlocks
/// blocks; each drawn chunk uses one geomipmap level (lod: every 2^lod-th
/// sample) chosen by its distance to the eye.
struct TerrainChunkDraw {
  int chunkX = 0, chunkZ = 0;  // chunk column / row (blocks chunkX * 64 ...)
  int lod = 0;
  int triangles = 0;           // surface + skirt triangles
};
struct TerrainStats {
  int chunksTotal = 0;         // chunks in the map
  int chunksDrawn = 0;
  int chunksCulled = 0;        // outside the view frustum or entirely in full fog
  std::int64_t trianglesDrawn = 0;
  int chunksUploaded = 0;      // chunk meshes built and uploaded during this frame
  bool materialsUploaded = false;  // the per-block material texture was (re)uploaded this frame
  std::size_t residentBytes = 0;   // chunk vertex data held on the GPU
  std::vector<TerrainChunkDraw> drawn;  // one entry per drawn chunk
};
inline constexpr int kTerrainChunkBlocks = 64;

enum class CameraMode { Orbit, Follow };

/// The eye sits at target + distance_m * (cos(pitch) sin(yaw), sin(pitch),
/// cos(pitch) cos(yaw)) and looks at target, Y up. Both modes use this; in
/// Follow the app moves target to the followed body every frame, so the
/// mouse still orbits around the moving body.
struct Camera {
  CameraMode mode = CameraMode::Orbit;
  Eigen::Vector3f target{0, 1, 0};  // m; orbit centre, or the followed point
  float yaw_rad = 0.6f;
  float pitch_rad = 0.35f;          // positive looks down from above
  float distance_m = 14.0f;
  float fovY_rad = 1.0f;            // vertical field of view
};

/// Shown by the Dear ImGui HUD.
struct HudStats {
  std::string scenario;
  double fps = 0;
  // ms per frame spent in each subsystem
  double physics_ms = 0, script_ms = 0, particles_ms = 0, render_ms = 0;
  double simTime_s = 0;
  int bodies = 0, contacts = 0;
  std::vector<std::string> messages;  // e.g. script errors, shown prominently (red)
};

/// Changed by keys and HUD buttons, read by the app loop.
struct Controls {
  bool paused = false;
  // Set for one frame by the single-step key/button; the app clears it. A
  // single step also pauses, so the app advances exactly one step and stops.
  bool stepOnce = false;
  float timeScale = 1.0f;             // slow motion: 1, 0.5, 0.25, 0.1
  bool screenshotRequested = false;   // screenshot key (F12); app clears it after saving
  bool quitRequested = false;         // window closed or Escape
};

/// The slow-motion levels that '-' / '=' and the HUD slider step through.
inline constexpr float kTimeScales[] = {1.0f, 0.5f, 0.25f, 0.1f};

struct WindowConfig {
  int width = 1280, height = 720;  // pixels; also the screenshot size
  std::string title = "Tumble";
  bool hud = true;
  bool forceOffscreen = false;     // use SDL's offscreen driver even if a display exists
  // Multisample anti-aliasing of the scene (1 = off). Clamped to what the
  // driver supports; Mesa llvmpipe supports 4.
  int msaaSamples = 4;
  // Terrain level of detail: a chunk takes the coarsest geomipmap level whose
  // (coarse) blocks are at most this many pixels wide on screen at the
  // chunk's nearest point. Smaller: more triangles, less popping.
  float terrainLodPixels = 16.0f;
};

class Renderer {
 public:
  // Creates the window and a GL 3.3 core context (libepoxy). If no display is
  // available (no DISPLAY/WAYLAND_DISPLAY, or SDL video init or window
  // creation fails), falls back to SDL's offscreen driver with Mesa. The error
  // message says what failed for each driver tried.
  static Result<std::unique_ptr<Renderer>> create(const WindowConfig& config);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  bool offscreen() const;  // true when running on the offscreen driver
  Camera& camera();
  /// Size in pixels of the frame drawFrame renders and screenshots store.
  Eigen::Vector2i framebufferSize() const;

  // Handles SDL events: close/Escape quit; P or Space pause; N single step;
  // '-'/'=' slower/faster slow motion; F12 screenshot; C toggles orbit/follow;
  // mouse drag orbits, wheel zooms. Also feeds ImGui; keys and mouse that the
  // HUD is using (typing in a field, dragging a slider) do not reach the game.
  void processEvents(Controls& controls);

  // Draws sky gradient, the terrain if any (chunked geomipmaps, per-block
  // textures, bump detail, fog), lit shapes (directional light + ambient,
  // checkered plane), debug lines and the HUD, then presents. If screenshotPath is
  // non-null the finished frame is written as an RGB PNG (see saveScreenshot);
  // the frame is still presented if that fails, and the Status says why.
  Status drawFrame(const FrameSnapshot& frame, const HudStats& hud, Controls& controls,
                   const char* screenshotPath = nullptr);

  // Writes the last frame drawFrame finished (HUD included) as an RGB PNG,
  // rows top-down, atomically (core/file_util writeFileAtomic). Reads the
  // renderer's own framebuffer, so it works without a visible window.
  Status saveScreenshot(const std::string& path);

  // Chunks and triangles of the terrain in the last drawFrame (all zero
  // without a terrain).
  const TerrainStats& terrainStats() const;

  struct Impl;  // SDL, GL and ImGui state; kept out of this header

 private:
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

}  // namespace tumble::render
