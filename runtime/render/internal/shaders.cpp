#include "render/internal/shaders.h"

#include <string>

namespace tumble::render::shaders {

// The lighting model, kept deliberately simple so shapes read clearly:
// one directional "sun" with Lambert diffuse and a faint Blinn-Phong
// highlight, plus a hemisphere ambient (sky colour from above, ground bounce
// from below) so faces turned away from the sun keep their shape. Distance
// fog blends into the sky's horizon colour, which hides the edge of the
// finite ground plane and the aliasing of far checker squares.

// The lit uniforms (set by internal/lit_uniforms.h) and the lighting and fog
// every lit pass shares: shapes, terrain and model meshes. Spliced into their
// fragment shaders after the #version line (litFragment below).
const char* const kLighting = R"glsl(
uniform vec3 uEye;
uniform vec3 uLightDirection;   // unit, towards the light
uniform vec3 uLightColor;
uniform vec3 uSkyAmbient;
uniform vec3 uGroundAmbient;
uniform vec3 uFogColor;
uniform float uFogDensity;      // 1/m
uniform int uShadowCascades;    // 0: no shadows (and no shadow map fetches)
uniform sampler2DArrayShadow uShadowMap;
uniform mat4 uShadowMatrix[3];  // world -> shadow texture coordinates and depth (0..1)
uniform vec3 uShadowFar;        // m along uViewForward where each cascade ends
uniform vec3 uShadowTexel;      // m per shadow texel in each cascade
uniform vec3 uViewForward;

// How much of the sun reaches this point, 0..1: the cascade by view depth,
// the point pushed out along the normal by a texel or two (no acne on
// slopes), 4 comparisons half a texel apart, each bilinear (hardware PCF),
// faded out over the last tenth of the shadowed distance.
float sunVisibility(vec3 position, vec3 n) {
  if (uShadowCascades == 0) return 1.0;
  float depth = dot(position - uEye, uViewForward);
  int c = 0;
  while (c < uShadowCascades && depth > uShadowFar[c]) ++c;
  if (c >= uShadowCascades) return 1.0;
  float slope = 1.0 - abs(dot(n, uLightDirection));
  vec4 p = uShadowMatrix[c] * vec4(position + n * uShadowTexel[c] * (0.6 + 1.5 * slope), 1.0);
  if (any(lessThan(p.xyz, vec3(0.0))) || any(greaterThan(p.xyz, vec3(1.0)))) return 1.0;
  float texel = 1.0 / float(textureSize(uShadowMap, 0).x);
  float lit = 0.0;
  lit += texture(uShadowMap, vec4(p.xy + vec2(-0.5, -0.5) * texel, float(c), p.z));
  lit += texture(uShadowMap, vec4(p.xy + vec2(0.5, -0.5) * texel, float(c), p.z));
  lit += texture(uShadowMap, vec4(p.xy + vec2(-0.5, 0.5) * texel, float(c), p.z));
  lit += texture(uShadowMap, vec4(p.xy + vec2(0.5, 0.5) * texel, float(c), p.z));
  lit *= 0.25;
  float last = uShadowFar[uShadowCascades - 1];
  return mix(lit, 1.0, smoothstep(0.9 * last, last, depth));
}

// Lambert sun + hemisphere ambient + a Blinn-Phong highlight of the given
// strength (0: none) and shininess.
vec3 sunAndSky(vec3 albedo, vec3 n, vec3 position, float highlight, float shininess) {
  float diffuse = max(dot(n, uLightDirection), 0.0);
  if (diffuse > 0.0) diffuse *= sunVisibility(position, n);
  vec3 ambient = mix(uGroundAmbient, uSkyAmbient, 0.5 * n.y + 0.5);
  vec3 color = albedo * (ambient + uLightColor * diffuse);
  if (highlight > 0.0 && diffuse > 0.0) {
    vec3 halfway = normalize(normalize(uEye - position) + uLightDirection);
    color += uLightColor * highlight * pow(max(dot(n, halfway), 0.0), shininess);
  }
  return color;
}

// Distance fog into the horizon colour, then linear -> sRGB.
vec4 fogged(vec3 color, float distance) {
  float d = distance * uFogDensity;
  color = mix(color, uFogColor, 1.0 - exp(-d * d));
  return vec4(pow(max(color, vec3(0.0)), vec3(1.0 / 2.2)), 1.0);
}
)glsl";

static std::string litFragment(const char* body) { return std::string("#version 330 core\n") + kLighting + body; }

const char* const kShapeVertex = R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in float aCapOffset;
layout(location = 3) in vec3 iPosition;
layout(location = 4) in vec4 iRotation;   // unit quaternion (x, y, z, w)
layout(location = 5) in vec3 iScale;
layout(location = 6) in float iHalfHeight;
layout(location = 7) in vec3 iColor;

uniform mat4 uViewProjection;

out vec3 vWorldPosition;
out vec3 vNormal;
out vec3 vColor;
out vec2 vPlaneCoord;

vec3 rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

void main() {
  vec3 local = aPosition * iScale + vec3(0.0, aCapOffset * iHalfHeight, 0.0);
  vec3 world = rotate(iRotation, local) + iPosition;
  vWorldPosition = world;
  // Normals transform with the inverse transpose of R*S, which is R*S^-1.
  vNormal = rotate(iRotation, aNormal / iScale);
  vColor = iColor;
  vPlaneCoord = local.xz;
  gl_Position = uViewProjection * vec4(world, 1.0);
}
)glsl";

// The large-scale brightness variation the terrain shaders and textured
// planes apply: two octaves of value noise over the ground, 0.75..1.25.
const char* const kGroundShade = R"glsl(
float hash(vec2 p) {
  uvec2 q = uvec2(ivec2(p)) * uvec2(1597334673u, 3812015801u);
  return float(((q.x ^ q.y) * 1597334673u) >> 8) * (1.0 / 16777216.0);
}
float valueNoise(vec2 p) {
  vec2 i = floor(p), f = p - i, u = f * f * (3.0 - 2.0 * f);
  return mix(mix(hash(i), hash(i + vec2(1, 0)), u.x), mix(hash(i + vec2(0, 1)), hash(i + vec2(1, 1)), u.x), u.y);
}
float groundShade(vec2 xz) {
  return 0.75 + 0.3 * valueNoise(xz * (1.0 / 41.0)) + 0.2 * valueNoise(xz * (1.0 / 13.0));
}
)glsl";

const std::string kShapeFragmentSource = litFragment((std::string(kGroundShade) + R"glsl(
in vec3 vWorldPosition;
in vec3 vNormal;
in vec3 vColor;
in vec2 vPlaneCoord;

uniform int uChecker;           // 1: 1 m checkerboard in local XZ (planes)
uniform int uGroundLayer;       // planes: 0 none, n > 0 ground texture layer n - 1 instead of the checkerboard
                                // (0, the default, keeps programs that never set it untextured)
uniform sampler2DArray uGround; // the terrain's ground textures (sRGB, sampled as linear)
uniform float uGroundPerMetre;  // ground texture repeats per metre

out vec4 fragColor;

// Box-filtered checkerboard (after Inigo Quilez): integrates the pattern over
// the pixel footprint, so squares fade to grey in the distance instead of
// shimmering.
float checker(vec2 p) {
  vec2 w = fwidth(p) + 1e-4;
  vec2 i = 2.0 * (abs(fract((p - 0.5 * w) * 0.5) - 0.5) -
                  abs(fract((p + 0.5 * w) * 0.5) - 0.5)) / w;
  return 0.5 - 0.5 * i.x * i.y;
}

void main() {
  vec3 n = normalize(vNormal);
  vec3 albedo = vColor;
  if (uGroundLayer > 0) {
    albedo *= texture(uGround, vec3(vPlaneCoord * uGroundPerMetre, float(uGroundLayer - 1))).rgb * groundShade(vPlaneCoord);
  } else if (uChecker != 0) {
    albedo *= mix(1.0, 0.55, checker(vPlaneCoord));
  }

  vec3 color = sunAndSky(albedo, n, vWorldPosition, 0.12, 40.0);
  fragColor = fogged(color, length(uEye - vWorldPosition));
}
)glsl").c_str());
const char* const kShapeFragment = kShapeFragmentSource.c_str();

// Sky: one triangle covering the screen (no vertex buffer; positions come
// from gl_VertexID), drawn at the far plane. The view ray through each pixel
// is rebuilt from the camera basis, which stays exact where inverting the
// projection at the far plane loses float precision.
const char* const kSkyVertex = R"glsl(
#version 330 core
out vec2 vNdc;
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  vNdc = p;
  gl_Position = vec4(p, 1.0, 1.0);
}
)glsl";

const char* const kSkyFragment = R"glsl(
#version 330 core
in vec2 vNdc;

uniform vec3 uRight;       // camera basis, world space
uniform vec3 uUp;
uniform vec3 uForward;
uniform vec2 uTanHalfFov;  // (tan(fovX / 2), tan(fovY / 2))
uniform samplerCube uSky;  // clear sky: gradient, sun glow and disc (linear RGB)
uniform sampler2D uClouds; // tiling plasma, 0..1
uniform float uCloudCover; // 0: no clouds (and no cloud texture fetches)
uniform vec2 uCloudOffset; // m the wind has moved the lower layer
uniform vec3 uCloudColor;  // lit cloud tops
uniform vec3 uCloudShadow; // dense cloud undersides
uniform vec3 uHorizonColor;
uniform float uFlash;      // lightning, 0..1

out vec4 fragColor;

void main() {
  vec3 dir = normalize(uForward + vNdc.x * uTanHalfFov.x * uRight +
                       vNdc.y * uTanHalfFov.y * uUp);
  vec3 color = texture(uSky, dir).rgb;
  if (uCloudCover > 0.0 && dir.y > 0.0) {
    // Two layers on flat planes, 1 km up: a thin, slow upper one and a
    // denser lower one. They thin out towards the horizon, so the horizon
    // keeps exactly the fog's colour.
    vec2 onPlane = dir.xz * (1000.0 / (dir.y + 0.02));
    float threshold = mix(0.85, -0.1, uCloudCover);
    float upper = texture(uClouds, (onPlane + 0.5 * uCloudOffset) * (1.0 / 7000.0) + vec2(0.37, 0.11)).r;
    float lower = texture(uClouds, (onPlane + uCloudOffset) * (1.0 / 2600.0)).r;
    float fade = smoothstep(0.0, 0.15, dir.y);
    float upperAlpha = 0.55 * smoothstep(threshold - 0.1, threshold + 0.2, upper) * fade;
    float lowerAlpha = smoothstep(threshold - 0.08, threshold + 0.12, lower) * fade;
    vec3 lowerColor = mix(uCloudColor, uCloudShadow, smoothstep(threshold, threshold + 0.45, lower));
    float haze = 1.0 - smoothstep(0.0, 0.35, dir.y);  // far clouds take the horizon's colour
    color = mix(color, mix(uCloudColor, uHorizonColor, haze), upperAlpha);
    color = mix(color, mix(lowerColor, uHorizonColor, haze), lowerAlpha);
  }
  color += uFlash * vec3(0.75, 0.8, 1.0);
  fragColor = vec4(pow(max(color, vec3(0.0)), vec3(1.0 / 2.2)), 1.0);
}
)glsl";

const char* const kLineVertex = R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColor;
uniform mat4 uViewProjection;
out vec3 vColor;
void main() {
  vColor = aColor;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)glsl";

const char* const kLineFragment = R"glsl(
#version 330 core
in vec3 vColor;
out vec4 fragColor;
void main() {
  fragColor = vec4(pow(clamp(vColor, 0.0, 1.0), vec3(1.0 / 2.2)), 1.0);
}
)glsl";

// Terrain: the same sun, hemisphere ambient and fog as the shapes, so the
// ground and the things on it read as one scene and fog meets the sky's
// horizon colour. On top:
// - per-block texture: the block under the fragment (texelFetch of the
//   material texture: r = texture layer, g = bump) picks a layer of the
//   texture array, so material borders follow block edges exactly.
// - bump detail: the normal is tilted by the gradient of two octaves of
//   value noise (analytic derivatives, after Inigo Quilez), scaled by the
//   block's bump byte and faded out with distance before it would alias.
// - a slow large-scale brightness variation, computed per vertex, hides
//   the texture's tiling.
// Measured on llvmpipe: arithmetic noise beats sampling a precomputed noise
// texture (trilinear fetches are the expensive part of a software
// rasteriser), and per-vertex work is nearly free next to per-pixel work.


const std::string kTerrainVertexSource = std::string(R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aNormal;   // packed 2_10_10_10, normalised
uniform mat4 uViewProjection;
out vec3 vWorldPosition;
out vec3 vNormal;
out float vShade;   // large-scale brightness variation, per vertex
)glsl") + kGroundShade + R"glsl(
void main() {
  vWorldPosition = aPosition;
  vNormal = aNormal.xyz;
  vShade = groundShade(aPosition.xz);
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)glsl";
const char* const kTerrainVertex = kTerrainVertexSource.c_str();

const std::string kTerrainFragmentSource = litFragment(R"glsl(
in vec3 vWorldPosition;
in vec3 vNormal;
in float vShade;

uniform usampler2D uMaterial;      // per block: r texture layer, g bump (0..255)
uniform sampler2DArray uTextures;  // sRGB layers, sampled as linear
uniform int uLayerCount;
uniform vec2 uOrigin;              // m, world x / z of sample (0, 0)
uniform float uSpacing;            // m per block
uniform ivec2 uBlocks;             // blocks along x / z
uniform float uTexturePerMetre;    // material texture repeats per metre
uniform float uDetailSlope;        // scale of the detail slope at bump 255
uniform bool uBlend;               // blend the four nearest blocks' surfaces (else each block's own)

out vec4 fragColor;
float hash(vec2 p) {
  uvec2 q = uvec2(ivec2(p)) * uvec2(1597334673u, 3812015801u);
  uint n = (q.x ^ q.y) * 1597334673u;
  return float(n >> 8) * (1.0 / 16777216.0);
}
vec3 noised(vec2 p) {
  vec2 i = floor(p);
  vec2 f = p - i;
  vec2 u = f * f * (3.0 - 2.0 * f);
  vec2 du = 6.0 * f * (1.0 - f);
  float a = hash(i), b = hash(i + vec2(1.0, 0.0));
  float c = hash(i + vec2(0.0, 1.0)), d = hash(i + vec2(1.0, 1.0));
  float k1 = b - a, k2 = c - a, k4 = a - b - c + d;
  return vec3(a + k1 * u.x + k2 * u.y + k4 * u.x * u.y, du * (vec2(k1, k2) + k4 * u.yx));
}

void main() {
  vec3 n = normalize(vNormal);
  vec2 xz = vWorldPosition.xz;

  vec2 blockCoord = (xz - uOrigin) / uSpacing;
  vec2 uv = xz * uTexturePerMetre;
  vec3 albedo;
  float bump;
  // Blending: the surfaces of the four blocks whose centres surround the
  // pixel, weighted bilinearly (eased, so a block's middle keeps its own
  // look) -- texture splatting of the painted layers. Where all four are
  // the same surface (most of the ground) it is the one-block path below,
  // bit for bit, and costs four integer fetches more.
  ivec2 block = clamp(ivec2(floor(blockCoord)), ivec2(0), uBlocks - 1);
  uvec2 material = texelFetch(uMaterial, block, 0).rg;
  bool blended = false;
  if (uBlend) {
    vec2 c = blockCoord - 0.5;
    ivec2 b0 = ivec2(floor(c));
    vec2 f = smoothstep(0.0, 1.0, c - vec2(b0));
    ivec2 lo = clamp(b0, ivec2(0), uBlocks - 1), hi = clamp(b0 + 1, ivec2(0), uBlocks - 1);
    uvec2 m00 = texelFetch(uMaterial, lo, 0).rg, m10 = texelFetch(uMaterial, ivec2(hi.x, lo.y), 0).rg;
    uvec2 m01 = texelFetch(uMaterial, ivec2(lo.x, hi.y), 0).rg, m11 = texelFetch(uMaterial, hi, 0).rg;
    if (m00 != m10 || m00 != m01 || m00 != m11) {
      vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
      albedo = w.x * texture(uTextures, vec3(uv, float(int(m00.r) % uLayerCount))).rgb +
               w.y * texture(uTextures, vec3(uv, float(int(m10.r) % uLayerCount))).rgb +
               w.z * texture(uTextures, vec3(uv, float(int(m01.r) % uLayerCount))).rgb +
               w.w * texture(uTextures, vec3(uv, float(int(m11.r) % uLayerCount))).rgb;
      bump = dot(w, vec4(m00.g, m10.g, m01.g, m11.g)) * (1.0 / 255.0);
      blended = true;
    }
  }
  if (!blended) {
    albedo = texture(uTextures, vec3(uv, float(int(material.r) % uLayerCount))).rgb;
    bump = float(material.g) * (1.0 / 255.0);
  }
  albedo *= vShade;

  // Bump: tilt the normal against the detail field's gradient, keeping only
  // the part of the tilt that lies in the surface's tangent plane.
  float distance = length(uEye - vWorldPosition);
  float strength = uDetailSlope * bump * clamp(1.5 - distance * (1.0 / 80.0), 0.0, 1.0);
  if (strength > 0.0) {
    // Detail height 0.5 noise(1.7 x) + 0.15 noise(5.3 x): gradient per metre.
    vec2 g = (noised(xz * 1.7).yz * 0.85 + noised(xz * 5.3 + 3.7).yz * 0.8) * strength;
    vec3 tilt = vec3(g.x, 0.0, g.y);
    n = normalize(n - (tilt - n * dot(n, tilt)));
  }

  fragColor = fogged(sunAndSky(albedo, n, vWorldPosition, 0.0, 1.0), distance);
}
)glsl");
const char* const kTerrainFragment = kTerrainFragmentSource.c_str();

// Terrain lit per vertex (the ground's simple shading, for the low preset):
// the same sun, hemisphere ambient, large-scale shade and fog as above, but
// computed at the vertices and interpolated, so a pixel costs a material
// fetch, a texture sample and one multiply. No bump detail and no sun
// shadows on the ground. On the ground's 1 m grid near the eye the light
// varies too slowly across a block for the difference to show; far away the
// coarse levels' big triangles smooth it.
const std::string kTerrainVertexLitSource = std::string(R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aNormal;   // packed 2_10_10_10, normalised
uniform mat4 uViewProjection;
uniform vec3 uEye;
uniform vec3 uLightDirection;   // unit, towards the light
uniform vec3 uLightColor;
uniform vec3 uSkyAmbient;
uniform vec3 uGroundAmbient;
uniform float uFogDensity;      // 1/m
out vec3 vWorldPosition;
out vec3 vLight;                // what multiplies the albedo (linear)
out float vFog;                 // 0..1 of the fog colour

)glsl") + kGroundShade + R"glsl(
void main() {
  vec3 n = normalize(aNormal.xyz);
  float shade = groundShade(aPosition.xz);
  float diffuse = max(dot(n, uLightDirection), 0.0);
  vLight = shade * (mix(uGroundAmbient, uSkyAmbient, 0.5 * n.y + 0.5) + uLightColor * diffuse);
  float d = length(uEye - aPosition) * uFogDensity;
  vFog = 1.0 - exp(-d * d);
  vWorldPosition = aPosition;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)glsl";
const char* const kTerrainVertexLit = kTerrainVertexLitSource.c_str();

const char* const kTerrainFragmentLit = R"glsl(
#version 330 core
in vec3 vWorldPosition;
in vec3 vLight;
in float vFog;

uniform usampler2D uMaterial;      // per block: r texture layer, g bump (unused here)
uniform sampler2DArray uTextures;  // sRGB layers, sampled as linear
uniform int uLayerCount;
uniform vec2 uOrigin;              // m, world x / z of sample (0, 0)
uniform float uSpacing;            // m per block
uniform ivec2 uBlocks;             // blocks along x / z
uniform float uTexturePerMetre;    // material texture repeats per metre
uniform vec3 uFogColor;

out vec4 fragColor;

void main() {
  vec2 xz = vWorldPosition.xz;
  ivec2 block = clamp(ivec2(floor((xz - uOrigin) / uSpacing)), ivec2(0), uBlocks - 1);
  float layer = float(int(texelFetch(uMaterial, block, 0).r) % uLayerCount);
  vec3 color = texture(uTextures, vec3(xz * uTexturePerMetre, layer)).rgb * vLight;
  color = mix(color, uFogColor, vFog);
  fragColor = vec4(pow(max(color, vec3(0.0)), vec3(1.0 / 2.2)), 1.0);
}
)glsl";

// Meshes of loaded models: the shapes' lighting and fog, an albedo of
// material colour x vertex colour x texture (an sRGB texture, so the sample
// is already linear). Two-sided: back faces turn their normal round, since
// model files do not agree on winding. Texels with alpha below one half are
// cut out (leaves, fences).
const char* const kMeshVertex = R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec3 aColor;

uniform mat4 uViewProjection;
uniform mat4 uModel;          // node frame -> world
uniform mat3 uNormalMatrix;   // inverse transpose of uModel's 3x3

out vec3 vWorldPosition;
out vec3 vNormal;
out vec2 vUv;
out vec3 vColor;

void main() {
  vec4 world = uModel * vec4(aPosition, 1.0);
  vWorldPosition = world.xyz;
  vNormal = uNormalMatrix * aNormal;
  vUv = aUv;
  vColor = aColor;
  gl_Position = uViewProjection * world;
}
)glsl";

const std::string kMeshFragmentSource = litFragment(R"glsl(
in vec3 vWorldPosition;
in vec3 vNormal;
in vec2 vUv;
in vec3 vColor;

uniform vec3 uDiffuse;        // linear material colour x instance tint
uniform vec3 uEmissive;       // linear, the light a lamp gives off itself
uniform int uHasTexture;
uniform sampler2D uTexture;   // sRGB, sampled as linear

out vec4 fragColor;

void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo = uDiffuse * vColor;
  if (uHasTexture != 0) {
    vec4 texel = texture(uTexture, vUv);
    if (texel.a < 0.5) discard;
    albedo *= texel.rgb;
  }
  vec3 lit = sunAndSky(albedo, n, vWorldPosition, 0.08, 32.0);
  fragColor = fogged(lit + uEmissive, length(uEye - vWorldPosition));
}
)glsl");
const char* const kMeshFragment = kMeshFragmentSource.c_str();

// Shadow depth: nothing to shade; the depth buffer is the output.
const char* const kDepthFragment = R"glsl(
#version 330 core
void main() {}
)glsl";

// Effects: additive strips and sprites. Lightning strips fade across their
// width (uv.y -1..1); flare sprites read a generated one-channel image.
// Colours are written as they are (already display values), times alpha.
const char* const kEffectsVertex = R"glsl(
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec2 aUv;
layout(location = 2) in vec4 aColor;
uniform mat4 uViewProjection;  // identity for screen-space sprites
out vec2 vUv;
out vec4 vColor;
void main() {
  vUv = aUv;
  vColor = aColor;
  gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
)glsl";

const char* const kEffectsFragment = R"glsl(
#version 330 core
in vec2 vUv;
in vec4 vColor;
uniform sampler2D uSprites;
uniform int uUseTexture;
out vec4 fragColor;
void main() {
  float a = uUseTexture != 0 ? texture(uSprites, vUv).r : pow(1.0 - abs(vUv.y), 2.0);
  fragColor = vec4(vColor.rgb * (vColor.a * a), 1.0);
}
)glsl";

}  // namespace tumble::render::shaders
