#pragma once
// GLSL 3.30 core sources of the render passes. Colours are linear RGB all the
// way through; each scene pass ends with the same pow(c, 1/2.2) encoding, so
// the framebuffer holds display values (no sRGB framebuffer needed, which
// not every window system offers) and screenshots match the screen. The HUD
// is drawn afterwards by Dear ImGui, whose colours are already display values.
namespace tumble::render::shaders {

extern const char* const kShapeVertex;
extern const char* const kShapeFragment;
extern const char* const kSkyVertex;
extern const char* const kSkyFragment;
extern const char* const kLineVertex;
extern const char* const kLineFragment;
extern const char* const kTerrainVertex;
extern const char* const kTerrainFragment;
extern const char* const kTerrainVertexLit;    // the ground lit per vertex (simple shading)
extern const char* const kTerrainFragmentLit;
extern const char* const kMeshVertex;
extern const char* const kMeshFragment;
// Shadow maps: depth only, paired with each pass's own vertex shader.
extern const char* const kDepthFragment;
// Lightning strips and lens flare sprites (effects_pass.h).
extern const char* const kEffectsVertex;
extern const char* const kEffectsFragment;

// Vertex attribute locations shared by the shape shader and its VAOs.
inline constexpr unsigned kAttribPosition = 0;
inline constexpr unsigned kAttribNormal = 1;
inline constexpr unsigned kAttribCapOffset = 2;
inline constexpr unsigned kAttribInstancePosition = 3;
inline constexpr unsigned kAttribInstanceRotation = 4;
inline constexpr unsigned kAttribInstanceScale = 5;
inline constexpr unsigned kAttribInstanceHalfHeight = 6;
inline constexpr unsigned kAttribInstanceColor = 7;

// Terrain shader locations.
inline constexpr unsigned kAttribTerrainPosition = 0;
inline constexpr unsigned kAttribTerrainNormal = 1;

// Mesh shader locations (mesh_pass.cpp).
inline constexpr unsigned kAttribMeshPosition = 0;
inline constexpr unsigned kAttribMeshNormal = 1;
inline constexpr unsigned kAttribMeshUv = 2;
inline constexpr unsigned kAttribMeshColor = 3;

// Line shader locations.
inline constexpr unsigned kAttribLinePosition = 0;
inline constexpr unsigned kAttribLineColor = 1;

}  // namespace tumble::render::shaders
