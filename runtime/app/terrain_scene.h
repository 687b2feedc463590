#pragma once
// Terrain in a scene: the app is where physics and terrain meet
// (ARCHITECTURE.md). TerrainScene owns a terrain::Terrain, exposes it to
// physics as a physics::HeightField and to the renderer as a
// render::TerrainSurface. A scene gets one only when asked for:
//
//   --set terrain.heightmap=PATH     16-bit (or 8-bit) grey PNG, with the
//                                    optional sidecar PATH.json (terrain_desc.h);
//                                    without a sidecar the map is centred on
//                                    the origin. Material layers beside it,
//                                    PATH-without-.png + ".texture.png",
//                                    ".bump.png", ".friction.png" (the drag
//                                    map: mu = value * 0.01) and ".sound.png",
//                                    replace the layers painted from slope and
//                                    height; `tumble terrain materials PATH`
//                                    writes those painted layers as a start
//   --set terrain.generate=SEED      a plasma terrain, deterministic per seed:
//     terrain.size=N                 samples per side (default 1025)
//     terrain.roughness=R            plasma roughness in (0, 1] (default 0.5)
//     terrain.spacing=M              metres between samples (default 1)
//     terrain.height=M               highest point above the lowest (default 40)
//     terrain.style=hills|island     island: sea around, a ridge and a ditch
//
// SceneOptions::terrainDefaults supplies the same keys per scenario; --set wins.
#include <map>
#include <memory>
#include <string>

#include "core/result.h"
#include "physics/height_field.h"
#include "render/renderer.h"
#include "terrain/terrain.h"
#include "vehicle/ground_softness.h"

namespace tumble::app {

/// physics::HeightField over a terrain::Terrain (no copy of the heights);
/// also the ground softness vehicles read (the terrain's softness layer).
class TerrainHeightField final : public physics::HeightField, public vehicle::GroundSoftness {
 public:
  explicit TerrainHeightField(const terrain::Terrain& terrain) : m_terrain(terrain) {}
  void visitTriangles(const Vec3& lo, const Vec3& hi, TriangleVisitor visit, void* ctx) const override;
  bool surfaceAt(Real x_m, Real z_m, Real* height_m, Vec3* normal) const override;
  Real frictionAt(Real x_m, Real z_m) const override;
  Real softnessAt(Real x_m, Real z_m) const override;
  bool rayCast(const Vec3& origin_m, const Vec3& unitDir, Real maxDistance_m,
               physics::HeightFieldHit* hit) const override;
  void bounds(Vec3* lo, Vec3* hi) const override;

 private:
  const terrain::Terrain& m_terrain;
};

/// Points `surface` at a terrain's heights and material layers with its
/// size, spacing, scale and origin (everything but the revision, which the
/// owner bumps when it changes the terrain).
void describeTerrainSurface(const terrain::Terrain& terrain, render::TerrainSurface& surface);

class TerrainScene {
 public:
  /// True if `settings` (terrain.* keys) ask for a terrain.
  static bool requested(const std::map<std::string, std::string>& settings);
  /// The terrain.* keys known and their numbers in range (what create checks
  /// before it reads a file); tools check settings with it before a run.
  static Status checkSettings(const std::map<std::string, std::string>& settings);
  /// Loads or generates the terrain; errors name the key or the file.
  /// `built`: a height map the scenario made (terrain.build in Lua), used
  /// unless the settings name a heightmap or a generate seed; it is moved from.
  static Result<std::unique_ptr<TerrainScene>> create(const std::map<std::string, std::string>& settings,
                                                      terrain::HeightMap* built = nullptr);

  const terrain::Terrain& terrain() const { return *m_terrain; }
  terrain::Terrain& terrain() { return *m_terrain; }
  const physics::HeightField& heightField() const { return *m_field; }
  const render::TerrainSurface& surface() const { return m_surface; }

 private:
  void fillSurface();
  std::unique_ptr<terrain::Terrain> m_terrain;
  std::unique_ptr<TerrainHeightField> m_field;
  render::TerrainSurface m_surface;
};

/// Paints the terrain's material maps from slope and height (rock where
/// steeper than ~35 degrees, snow in the top 15% of the height range, sand
/// just above the sea of an island, mud patches on flat low ground, grass
/// elsewhere): texture, bump, friction (the drag map physics reads) and sound.
void paintMaterials(terrain::Terrain& terrain, bool island);

/// "maps/alps.png" + Friction -> "maps/alps.friction.png" (see the header comment).
std::string materialLayerPath(const std::string& heightMapPath, terrain::MaterialLayer layer);
/// Replaces each layer whose file exists beside the height map; a layer file
/// of the wrong size or format is an error naming the file and the size expected.
Status loadMaterialLayersBeside(terrain::Terrain& terrain, const std::string& heightMapPath);
/// Writes all four layers beside the height map (each atomically).
Status saveMaterialLayersBeside(const terrain::Terrain& terrain, const std::string& heightMapPath);

}  // namespace tumble::app
