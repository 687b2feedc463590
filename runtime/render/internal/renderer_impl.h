#pragma once
// Renderer's private state, shared by renderer.cpp (frames, screenshots) and
// event_handling.cpp (input). Members are declared in creation order so they
// are destroyed in reverse: HUD and GL objects go while the context that owns
// them is still alive, the context and window last.
#include <memory>

#include "render/internal/convex_mesh_pass.h"
#include "render/internal/effects_pass.h"
#include "render/internal/environment.h"
#include "render/internal/gl_context.h"
#include "render/internal/hud.h"
#include "render/internal/line_pass.h"
#include "render/internal/particles_pass.h"
#include "render/internal/mesh_pass.h"
#include "render/internal/render_targets.h"
#include "render/internal/shadow_maps.h"
#include "render/internal/shape_pass.h"
#include "render/internal/sky_pass.h"
#include "render/internal/surface_pass.h"
#include "render/internal/terrain_pass.h"
#include "render/renderer.h"

namespace tumble::render {

struct Renderer::Impl {
  WindowConfig config;
  std::unique_ptr<GlContext> context;
  RenderTargets targets;
  SkyPass sky;
  ShadowMaps shadowMaps;     // no GPU memory until a frame with shadows on
  bool reportedShadowError = false;
  ShapePass shapes;
  ConvexMeshPass convexMeshes;  // no GPU memory until a frame has a ConvexMesh
  LinePass lines;
  SurfacePass surfaces;      // cloth; creates nothing until the first frame with a surface
  bool reportedSurfaceError = false;
  std::vector<DrawParticle> rain;  // this frame's rain streaks (storm), capacity kept
  TerrainPass terrain;       // creates nothing until the first frame with a terrain
  ParticlesPass particles;   // creates nothing until the first frame with particles
  EffectsPass effects;       // lightning and lens flare; creates nothing until needed
  bool reportedEffectsError = false;
  TerrainStats terrainStats;
  MeshPass meshes;           // creates nothing until the first frame with a model
  MeshStats meshStats;
  bool reportedMeshError = false;
  std::unique_ptr<Hud> hud;  // null when config.hud is false
  Environment environment;
  Camera camera;
  bool hasFrame = false;         // the last frame was finished in the frame target, for saveScreenshot
  bool reportedGlError = false;  // GL errors are logged once, not every frame
  bool reportedTerrainError = false;
  bool reportedParticleError = false;
  bool dragging = false;         // mouse button held down on the scene
  EventHook eventHook;           // the app's (input); may be empty
  TuningPanel* tuning = nullptr;  // see Renderer::setTuningPanel
  RenderQuality quality;          // see Renderer::setQuality (created from config)
};

}  // namespace tumble::render
