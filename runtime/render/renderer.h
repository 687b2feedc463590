#pragma once
// The render module: an SDL2 window (or SDL's offscreen driver with Mesa when
// there is no display), an OpenGL 3.3 core context through libepoxy, and one
// call per frame that draws what the simulation handed over.
//
// Index
//   DrawShape, DebugLine, FrameSnapshot   what the renderer reads (plain data)
//   DrawParticle                          one camera-facing particle billboard
//   DrawSurface                           a triangle surface remade every frame (cloth), lit on both sides
//   ModelInstance, MeshStats              models (model.h) placed in the frame; what was drawn
//   ConvexMeshData                        a convex mesh (physics hull) drawn flat shaded
//   TerrainSurface, TerrainStats          height-field view the app fills; what was drawn
//   Camera, CameraMode                    orbit / follow camera
//   HudStats, Controls                    the Dear ImGui HUD: shown / changed
//   TuningItem, TuningPanel               the tuning panel (F2): tunables shown / edited
//   WindowConfig, Renderer                window, events, drawing, screenshots
//   EventHook, HudPanel                   the app's share of events and HUD (input, menus)
//
// render is a leaf: it depends on core only. The app copies simulation state
// into a FrameSnapshot; nothing here reads physics, script or particles, and
// the simulation never reads render (ARCHITECTURE.md).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "render/sky.h"

union SDL_Event;  // render.h does not include SDL; hooks get events by reference

namespace tumble::render {

/// ConvexMesh stays last: the kinds before it are instanced batches (ShapePass).
enum class ShapeKind { Box, Sphere, Capsule, Plane, Cylinder, ConvexMesh };

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
  float radius_m = 0.5f;                          // Sphere, Capsule, Cylinder
  // Capsule: half length of the core segment along local Y (caps excluded),
  // so the capsule's total height is 2 * (halfHeight_m + radius_m).
  // Cylinder: half its height along local Y (flat caps).
  float halfHeight_m = 0.5f;
  std::shared_ptr<const ConvexMeshData> convexMesh;  // ConvexMesh: the mesh (shared; not copied per frame)
  Eigen::Vector3f color{0.8f, 0.8f, 0.8f};  // linear RGB 0..1; Plane: colour of the light squares, or the texture's tint
  // Plane only: -1 draws 1 m checker squares; 0..kTerrainTextureCount-1 the
  // terrain's ground texture of that index (0 grass, 1 rock, 2 sand, 3 mud,
  // 4 snow, 5 gravel, 6 dirt, 7 moss), tiling every 4 m, times color.
  int groundTexture = -1;
  bool sleeping = false;                    // drawn a little darker
};

struct DebugLine {
  Eigen::Vector3f a, b;                     // m, world
  Eigen::Vector3f color{1, 1, 0};           // linear RGB 0..1
  bool overlay = false;  // drawn over everything (the designer's gizmo), not hidden by what stands in front
};

/// One particle, drawn as a camera-facing square with a soft round sprite
/// (made in the shader; no texture). The app fills these from the particle
/// system; render never includes particles.
struct DrawParticle {
  Eigen::Vector3f position{0, 0, 0};  // m, world: the centre
  float size_m = 0.2f;                // width of the square
  Eigen::Vector4f color{1, 1, 1, 1};  // linear RGB 0..1 (more glows, additive) and alpha 0..1
  float angle_rad = 0;                // turn in the screen plane (round particles only)
  // Non-zero: drawn as a streak along this world vector (its length on
  // screen is added to the size), e.g. velocity x 0.03 s for rain.
  Eigen::Vector3f stretch_m{0, 0, 0};
};

/// A triangle surface handed over anew every frame (cloth): drawn smooth
/// shaded with normals the renderer averages over the triangles at each
/// vertex, lit on both sides (a back face takes the flipped normal), and
/// casting sun shadows. Triangles naming a vertex past `positions` are skipped.
struct DrawSurface {
  std::vector<Eigen::Vector3f> positions;   // m, world
  std::vector<std::uint32_t> indices;       // triangle list
  Eigen::Vector3f color{0.8f, 0.8f, 0.8f};  // linear RGB 0..1, both sides
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
  // Optional, for editors: the samples (inclusive, i0..i1 x j0..j1) whose
  // heights or block materials changed between revision dirtySinceRevision
  // and revision. If the renderer last drew dirtySinceRevision and nothing
  // but the revision changed, it rebuilds only the chunks those samples
  // touch (their meshes, normals and bounds, one sample around for the
  // normals) and re-uploads only their blocks' materials; otherwise, or
  // with an empty rectangle (i1 < i0), everything as above. The app unites
  // the rectangles of the edits made since the frame it last handed over.
  std::uint64_t dirtySinceRevision = 0;
  int dirtyI0 = 0, dirtyJ0 = 0, dirtyI1 = -1, dirtyJ1 = -1;
};

/// Number of built-in procedural terrain textures (see TerrainSurface).
inline constexpr int kTerrainTextureCount = 8;

struct Model;  // render/model.h

/// One model drawn this frame: model space -> world is
/// translate(position) * rotate(orientation) * scale(scale). The renderer
/// uploads a model the first time it sees it and frees it once no snapshot
/// and nobody else holds the shared_ptr any more.
struct ModelInstance {
  std::shared_ptr<const Model> model;
  Eigen::Vector3f position{0, 0, 0};  // m, world
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();
  Eigen::Vector3f scale{1, 1, 1};     // per model axis, unitless
  Eigen::Vector3f tint{1, 1, 1};      // linear RGB factor on every material colour
};

/// Everything the renderer reads of the simulation.
struct FrameSnapshot {
  std::vector<DrawShape> shapes;
  std::vector<DebugLine> lines;
  double simTime_s = 0;
  const TerrainSurface* terrain = nullptr;  // optional; null: no terrain, no terrain GPU memory
  // Particles: alpha-blended ones are sorted back to front by the renderer;
  // additive ones are drawn after them in any order. Both depth-tested
  // against the scene, neither writes depth. Empty: no particle GPU objects.
  std::vector<DrawParticle> particles;
  std::vector<DrawParticle> additiveParticles;
  std::vector<ModelInstance> models;        // textured meshes (mesh pass); empty: no mesh GPU memory
  SkySettings sky;                          // time of day, sun, fog, clouds, weather (render/sky.h)
  std::vector<DrawSurface> surfaces;        // cloth; empty: no surface GPU objects
};

/// What the mesh pass did in the last drawFrame (Renderer::meshStats).
struct MeshStats {
  int instances = 0;          // ModelInstances handed over
  int nodesTested = 0;        // tree nodes looked at by view culling
  int nodesCulled = 0;        // nodes with meshes left out (outside the view)
  int drawCalls = 0;          // one per visible (node, mesh)
  int materialSwitches = 0;   // times the bound material (colour, texture) changed, the first bind included
  std::int64_t triangles = 0;
  int modelsResident = 0;     // models whose meshes and textures are on the GPU
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
  int chunksInvalidated = 0;       // chunks a dirty rectangle (TerrainSurface::dirtyI0..) made rebuild this frame
  // Wall time (ms) the renderer spent this frame bringing the terrain up to
  // date: dropping the chunks a change touched, uploading the changed block
  // materials, and building and uploading chunk meshes (vertices and
  // normals). The designer's brush cost on screen; 0 when nothing changed
  // and every chunk in view was resident.
  double updateTime_ms = 0;
  std::size_t residentBytes = 0;   // chunk vertex data held on the GPU
  std::vector<TerrainChunkDraw> drawn;  // one entry per drawn chunk
};
inline constexpr int kTerrainChunkBlocks = 64;

// Chase, Hood and Cockpit follow a body (render/camera_rig.h).
enum class CameraMode { Orbit, Follow, Chase, Hood, Cockpit };

/// Orbit and Follow: the eye sits at target + distance_m * (cos(pitch)
/// sin(yaw), sin(pitch), cos(pitch) cos(yaw)) and looks at target, Y up; in
/// Follow the app moves target to the followed body every frame, so the
/// mouse still orbits around the moving body. Chase, Hood and Cockpit: the
/// app (CameraRig) sets eye_m, target and up every frame.
struct Camera {
  CameraMode mode = CameraMode::Orbit;
  Eigen::Vector3f target{0, 1, 0};  // m; orbit centre, or the followed point
  float yaw_rad = 0.6f;
  float pitch_rad = 0.35f;          // positive looks down from above
  float distance_m = 14.0f;
  float fovY_rad = 1.0f;            // vertical field of view
  Eigen::Vector3f eye_m{0, 3, 10};  // m; Chase / Hood / Cockpit only
  Eigen::Vector3f up{0, 1, 0};      // Chase / Hood / Cockpit: the view's up direction
  // The camera key (C) steps into Chase, Hood and Cockpit too; the app sets
  // it when the scenario names a body to follow (camera.set_mode).
  bool vehicleModes = false;
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
  bool quitRequested = false;         // window closed (Escape opens the app's pause menu instead)
  bool tuningPanelVisible = false;    // F2 or the HUD's "Tune" button toggles the tuning panel
  // F3 or the HUD's "Collision" button: the app draws what collides instead
  // of what models show (static meshes as wireframe triangles).
  bool collisionView = false;
  // The debug panel (FPS, ms per subsystem, sim controls), top left. Off for
  // players; the app's debug_panel action (F4) toggles it.
  bool debugPanelVisible = false;
};

/// One tunable as the tuning panel shows it (plain data; the app copies it
/// from the scenario's tunables each frame and applies edits back).
struct TuningItem {
  enum class Kind { Number, Bool, Choice };
  std::string name, unit, description;  // unit: shown after the value, e.g. "m/s^2"
  Kind kind = Kind::Number;
  double value = 0;                     // Number: the value; Bool: 0/1; Choice: index into choices
  double defaultValue = 0;
  double min = 0, max = 0;              // Number: inclusive limits; non-finite means none
  double step = 0;                      // Number: 0 = continuous
  std::vector<std::string> choices;     // Choice
  bool userSet = false;                 // differs from the script's default by the user's hand
  // Written by the panel during drawFrame, read and cleared by the app:
  bool edited = false;                  // `value` was changed in the panel
  bool resetRequested = false;          // the item's "reset" button
};

/// What the panel shows and what it asks for. The renderer draws it while
/// Controls::tuningPanelVisible (see Renderer::setTuningPanel).
struct TuningPanel {
  std::string title;            // e.g. the scenario's name
  std::string overridesPath;    // where "Save" writes; shown in the panel
  std::string status;           // last save / load message
  std::vector<TuningItem> items;
  bool saveRequested = false;   // set by the "Save" button; the app clears it
  bool resetAllRequested = false;
};

/// How the panel edits an item: a slider between two finite limits, a drag
/// field otherwise, a checkbox for Bool, a drop-down for Choice.
enum class TuningWidget { Slider, Drag, Checkbox, Combo };
TuningWidget tuningWidgetFor(const TuningItem& item);
/// The value as the panel prints it: "9.81 m/s^2", "on", "hard".
std::string tuningValueText(const TuningItem& item);
/// Snaps a number to the item's step (from min, or 0) and clamps it to its limits.
double tuningSnap(const TuningItem& item, double value);

/// The slow-motion levels that '-' / '=' and the HUD slider step through.
inline constexpr float kTimeScales[] = {1.0f, 0.5f, 0.25f, 0.1f};

/// Sees each SDL event (after the HUD) before the renderer's own keys and
/// mouse. hudWants: the HUD uses this event's device right now (typing, a
/// slider, the pointer over a HUD window). Return true to consume the event:
/// the renderer then does nothing with it. The app hands events to the
/// input module this way (render never includes input).
using EventHook = std::function<bool(const SDL_Event& event, bool hudWants)>;
/// Builds extra Dear ImGui windows inside the HUD's frame, with the HUD's
/// ImGui context current (the app's bindings menu). It may run twice in a
/// frame when the HUD lays itself out first.
using HudPanel = std::function<void()>;

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
  // The ground's detailed shading: light per pixel with sun shadows and bump
  // detail near the eye (two octaves of noise, faded out by 120 m). Off: the
  // ground is lit per vertex, without bump detail or sun shadows on it (a
  // third of the ground's cost on software OpenGL; the low preset).
  bool terrainDetail = true;
  // Neighbouring blocks' surfaces blend into each other across a block
  // (texture splatting: the four nearest blocks' textures and bump,
  // weighted bilinearly) instead of each block showing its own surface up
  // to its edge. Only with terrainDetail; where the four are the same
  // surface the pixel is the unblended one. The high preset.
  bool terrainBlend = false;
  // The look (sky.h, README "Sky, weather and shadows"). Quality presets set
  // these; Renderer::settings() changes them between frames.
  bool clouds = true;              // the two moving cloud layers (off: the clear sky cube only)
  int skyCubeSize = 128;           // texels per sky cube face edge (16..1024)
  bool shadows = true;             // cascaded sun shadows (off: no shadow pass, no shadow lookups)
  int shadowMapSize = 1024;        // texels per cascade's depth map edge (64..4096)
  int shadowCascades = 3;          // 1..3 slices of the view, each with its own map
  float shadowDistance_m = 60.0f;  // shadows end (fading out over the last tenth) this far along the view
  bool lensFlare = true;           // the sun's flare (an occlusion query and 7 sprites when the sun is in view)
  bool lightning = true;           // bolts and sky flashes in Weather::Storm
};

/// What a quality preset changes in the renderer (the app's presets:
/// app/player_settings.h). Applied from the next frame on.
struct RenderQuality {
  float resolutionScale = 1.0f;  ///< the 3D scene at this fraction of the window's pixels (0.25..1), HUD sharp
  float farPlane_m = 2000.0f;    ///< nothing is drawn beyond this distance
  float fogDistance_m = 250.0f;  ///< fog reaches 63 % here (1 - exp(-(d / this)^2)); terrain beyond 2.5x is culled
  float terrainLodPixels = 16.0f;  ///< as WindowConfig::terrainLodPixels
  bool terrainDetail = true;       ///< as WindowConfig::terrainDetail
  bool terrainBlend = false;       ///< as WindowConfig::terrainBlend
  int msaaSamples = 4;           ///< 1 = off; as WindowConfig::msaaSamples
  bool shadows = true;           ///< cascaded sun shadows (WindowConfig::shadows)
  int shadowMapSize = 1024;      ///< texels per cascade's map edge (WindowConfig::shadowMapSize)
  int shadowCascades = 3;        ///< WindowConfig::shadowCascades
  bool lensFlare = true;         ///< WindowConfig::lensFlare
  /// Rain streaks kept around the eye while the sky's weather is Storm
  /// (0: no rain). The app's presets give a quarter of their particle budget.
  int rainDrops = 4000;
};

/// An image uploaded for the HUD's panels (ImGui::Image(ImTextureID(texture), ...)).
struct UiImage {
  std::uintptr_t texture = 0;  ///< the GL texture name; 0: none
  int width = 0, height = 0;   ///< pixels
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
  /// SDL's id of the window (events sent to it carry this id).
  std::uint32_t windowId() const;
  Camera& camera();
  /// The configuration, for changes between frames: the look fields (clouds,
  /// skyCubeSize, shadows, shadowMapSize, shadowCascades, shadowDistance_m),
  /// msaaSamples and terrainLodPixels take effect on the next drawFrame.
  WindowConfig& settings();
  /// Size in pixels of the frame drawFrame renders and screenshots store.
  Eigen::Vector2i framebufferSize() const;
  /// The ray from the eye through view point (x, y), both -1..1 with y up
  /// (pointer picking): origin (m, world) and unit direction.
  std::pair<Eigen::Vector3f, Eigen::Vector3f> viewRay(float x, float y) const;
  /// Where a world point (m) appears in the view: x and y in -1..1 with y up
  /// inside the view (the inverse of viewRay); nothing when it is behind the eye.
  std::optional<Eigen::Vector2f> viewPoint(const Eigen::Vector3f& world_m) const;

  // Handles SDL events: window close quits (Escape does not); P or Space pause; N single step;
  // '-'/'=' slower/faster slow motion; F12 screenshot; F2 tuning panel; F3 collision view; C steps through the
  // camera modes (orbit, follow, and with Camera::vehicleModes chase, hood, cockpit);
  // mouse drag orbits, wheel zooms. Also feeds ImGui; keys and mouse that the
  // HUD is using (typing in a field, dragging a slider) do not reach the game.
  void processEvents(Controls& controls);
  /// See EventHook. One hook; setting another replaces it.
  void setEventHook(EventHook hook);
  /// See HudPanel. Panels are built in the order added, after the HUD's own windows.
  void addHudPanel(HudPanel panel);

  // Draws the sky (cube, clouds), the terrain if any (chunked geomipmaps, per-block
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

  // The tuning panel drawn (while Controls::tuningPanelVisible) by the
  // following drawFrame calls; its edits are written into *panel. Null: none
  // (the HUD's "Tune" button is then hidden). The app owns the panel.
  void setTuningPanel(TuningPanel* panel);

  // Chunks and triangles of the terrain in the last drawFrame (all zero
  // without a terrain).
  const TerrainStats& terrainStats() const;
  // Instances, culled nodes, draw calls and material switches of the mesh
  // pass in the last drawFrame.
  const MeshStats& meshStats() const;

  /// The quality preset's settings, from the next frame on.
  void setQuality(const RenderQuality& quality);
  const RenderQuality& quality() const;
  /// Window size (px) and fullscreen (the desktop's resolution); offscreen
  /// only the size changes.
  void setWindowMode(int width, int height, bool fullscreen);
  /// The window's size now (SDL_GetWindowSize), pixels.
  std::pair<int, int> windowSize() const;

  /// Decodes an image file (PNG, JPEG; stb_image) into an RGBA texture for
  /// HUD panels. Free it with freeUiImage while the renderer lives.
  Result<UiImage> loadUiImage(const std::string& path);
  /// An RGBA texture (8 bits a channel, rows top first) made from pixels the
  /// app computed, e.g. the minimap: one textured quad to draw instead of a
  /// rectangle per cell. Free it with freeUiImage.
  Result<UiImage> makeUiImage(const std::uint8_t* rgba, int width, int height);
  void freeUiImage(UiImage& image);
  /// A square picture of one model for a HUD panel (the designer's object
  /// palette): the model alone in the default daylight, seen from the front
  /// left and above, filling the picture. Drawn into a target of its own, so
  /// the window's frame is untouched; size_px is 16..512. Free it with
  /// freeUiImage.
  Result<UiImage> renderModelThumbnail(const std::shared_ptr<const Model>& model, int size_px);

  struct Impl;  // SDL, GL and ImGui state; kept out of this header

 private:
  explicit Renderer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

}  // namespace tumble::render
