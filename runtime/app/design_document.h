#pragma once
// DesignDocument: what the scenario designer edits, without a window. A
// terrain (heights and material layers), placed objects, the vehicle start
// and the chosen car; every edit is undoable; the whole of it saves as a mod
// scenario that plays with `tumble play MOD:SCENARIO` and opens again here.
// The designer's window, camera and mouse tools are built on top of this
// (they call these functions and draw terrain() and objects()).
//
// Sections: new maps, editing the terrain, surfaces, objects, start and
// car, undo, saving and opening. docs/designer.md describes the files a save
// writes and the Lua scenario it generates.
//
// Coordinates are world metres, Y up (terrain_desc.h). The UI passes x and z
// (from its ray onto the ground); the document computes y from the terrain.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/result.h"
#include "terrain/brushes.h"
#include "terrain/terrain.h"

namespace tumble::render {
struct TerrainSurface;
}

namespace tumble::app {

using SampleRect = terrain::SampleRect;  ///< inclusive height-map samples touched
using BrushKind = terrain::BrushKind;
using Brush = terrain::Brush;            ///< radius, strength (m/s), falloff, flatten height, seed

// ---- new maps ---------------------------------------------------------------------

struct NewMapOptions {
  int size_samples = 513;            ///< samples per side, 2..4097 (flat, plasma); image: 0 keeps its size,
                                     ///< else its longer side is resampled (bicubic) to this many samples
  double spacing_m = 1.0;            ///< metres between neighbouring samples (0 < s <= 1000)
  std::string generator = "flat";    ///< "flat", "plasma" or "image"
  std::uint64_t seed = 1;            ///< plasma
  double roughness = 0.5;            ///< plasma, in (0, 1]: 0.3 rolling, 0.5 hills, 0.7 craggy
  std::string imagePath;             ///< image: a grey or RGB PNG, 8 or 16 bit, any size up to kMaxImportSide
  double minHeight_m = 0.0;          ///< world height of the value 0 (image black, plasma lowest)
  double maxHeight_m = 40.0;         ///< world height of the value 65535 (image white, plasma highest), > min
  double flatHeight_m = 0.0;         ///< flat: the ground's height, within [min, max]
  bool centred = true;               ///< true: the map's middle is at x = z = 0
  double originX_m = 0.0, originZ_m = 0.0;  ///< when not centred: world x, z of sample (0, 0)
};

/// Largest image side accepted for import; sides above terrain::kMaxHeightMapSide
/// are resampled down to it (the spacing grows by the same ratio, so the
/// map covers the same ground).
constexpr int kMaxImportSide = 8193;

// ---- surfaces -----------------------------------------------------------------------

/// A named material a brush paints: every layer of the material maps.
struct Surface {
  std::string name;                   ///< "grass", "rock", ...
  terrain::SurfaceMaterial material;  ///< texture, friction (mu*100), bump, softness (*100), sound
};
/// grass, rock, sand, mud, snow, gravel, dirt, moss, asphalt, ice (the
/// generated terrains' grass, rock, sand, mud and snow are the same bytes).
const std::vector<Surface>& surfacePalette();
/// nullptr if no palette entry has this name.
const Surface* findSurface(const std::string& name);

// ---- objects ------------------------------------------------------------------------

enum class PlacedKind { Model, Box, Barrel, Ragdoll, Gate, Trigger, Emitter };
/// "model", "box", "barrel", "ragdoll", "gate", "trigger", "emitter".
const char* placedKindName(PlacedKind kind);

struct PlacedObject {
  PlacedKind kind = PlacedKind::Model;
  /// Model: "MOD:path/in/mod.obj" (a model of a loaded mod); Emitter: "MOD:name"
  /// of an emitter definition (base:smoke, base:fire, base:rain); else unused.
  std::string asset;
  /// The point on the ground under the object's origin, m. addObject and
  /// moveObject set y to the terrain height at (x, z) (off the map: the
  /// height at the nearest edge).
  Vec3 position_m = Vec3::Zero();
  double yaw_rad = 0.0;               ///< rotation about +Y
  /// Model: scale factor per axis (> 0). Box, Trigger: full size x, y, z, m.
  /// Barrel: diameter, height, (unused) m. Gate: width between the posts,
  /// post height, (unused) m. Ragdoll: x = body scale (1 = 1.8 m adult).
  /// Emitter: unused.
  Vec3 scale = Vec3::Ones();
  std::string collision = "mesh";     ///< Model: "mesh", "box" or "none"
  int order = 0;                      ///< Gate: its place in the lap, 1 first (gates are driven in this order)
  double mass_kg = 0.0;               ///< Box, Barrel: 0 = from the size at the density of wood (600 kg/m^3)
  bool operator==(const PlacedObject&) const = default;
};

/// "MOD:path" of every model file (render::hasModelExtension: .obj, .gltf,
/// .glb, .fbx, .dae, .3ds) under assets/ of each mod found in `modFolders` (e.g.
/// modSearchDirs({})), sorted: the object palette. Thumbnails are the UI's.
std::vector<std::string> listModelAssets(const std::vector<std::string>& modFolders);
/// "MOD:name" of every emitter definition (emitters/NAME.lua) of those mods, sorted.
std::vector<std::string> listEmitters(const std::vector<std::string>& modFolders);

struct VehicleStart {
  Vec3 position_m = Vec3::Zero();  ///< on the ground (y from the terrain)
  double heading_rad = 0.0;        ///< 0 faces +Z (vehicle.spawn's heading)
  bool operator==(const VehicleStart&) const = default;
};

/// The scenario's sky and weather (environment.set in the saved scenario,
/// and what the designer draws): the outdoor afternoon of base:drive unless
/// changed.
struct DesignSky {
  double timeOfDay_h = 16.5;    ///< local solar time, hours in [0, 24]
  std::string weather = "clear";  ///< "clear", "cloudy" or "storm"
  double cloudCover = 0.45;     ///< fraction of the sky under the cloud layers, [0, 1]
  bool operator==(const DesignSky&) const = default;
};

/// Empty if `sky` is one environment.set accepts, else what is wrong: "'FIELD': expected ...".
std::string checkSky(const DesignSky& sky);

/// Everything of a design besides the terrain: what an object edit's undo step keeps.
struct DesignMeta {
  std::map<std::uint32_t, PlacedObject> objects;
  std::uint32_t nextId = 1;                ///< the id the next added object gets
  VehicleStart start;
  std::string vehicle = "base:hatchback";  ///< the car driven from the start, "MOD:NAME"
  std::string title = "A designed course"; ///< the scenario's title
  DesignSky sky;
  bool operator==(const DesignMeta&) const = default;
};

// ---- the document -------------------------------------------------------------------

class DesignDocument {
 public:
  /// A new map. Errors name the field (size_samples, spacing_m, generator,
  /// roughness, imagePath: the file and what is wrong, ...) and the range allowed.
  static Result<DesignDocument> create(const NewMapOptions& options);
  /// What saveAsMod wrote: <modDir>/designs/<scenario>.design.json and the
  /// files it names. Errors name the file and field.
  static Result<DesignDocument> open(const std::string& modDir, const std::string& scenario);

  DesignDocument(DesignDocument&&) noexcept;
  DesignDocument& operator=(DesignDocument&&) noexcept;
  ~DesignDocument();

  /// Stable for the document's life (a heap object: moving the document keeps it).
  terrain::Terrain& terrain();
  const terrain::Terrain& terrain() const;
  /// Terrain height under (x, z), m (clamped to the edge off the map).
  double groundHeight_m(double x_m, double z_m) const;
  /// Points `out` at the heights and material layers (render::TerrainSurface)
  /// and sets its revision to revision(). Call again after a new map/open.
  void fillSurface(render::TerrainSurface& out) const;

  // --- edits: each is one undo step; beginStroke .. endStroke groups many ---
  void beginStroke();
  void endStroke();
  bool inStroke() const;

  /// Brush dab at (x, z) over dt_s seconds of holding the button.
  SampleRect dab(const Brush& brush, double x_m, double z_m, double dt_s);
  /// Ridge (ridge = true) or ditch along from -> to (x, z in m), width m, height m.
  SampleRect line(bool ridge, Vec2 from_m, Vec2 to_m, double width_m, double height_m);
  /// Paints `surface` on the blocks within radius_m; physics reads the new
  /// friction and softness at once (frictionAt / softnessAt).
  SampleRect paint(const Surface& surface, double x_m, double z_m, double radius_m);
  /// Union of the samples changed since the last call (edits, undo, redo):
  /// what the renderer rebuilds. Cleared by the call.
  SampleRect takeChangedSamples();

  /// Returns its id; 0 (nothing added) for a position that is not finite
  /// or a scale that is not > 0 on every axis.
  std::uint32_t addObject(const PlacedObject& object);
  /// Replaces the object (y snapped); false if no such id or the same checks as addObject fail.
  bool moveObject(std::uint32_t id, const PlacedObject& object);
  bool removeObject(std::uint32_t id);
  std::uint32_t duplicateObject(std::uint32_t id);  ///< 0 if no such id
  const std::map<std::uint32_t, PlacedObject>& objects() const;
  /// Objects, next id, start, car and title together.
  const DesignMeta& meta() const;

  void setStart(Vec3 position_m, double heading_rad);  ///< y snapped to the ground
  const VehicleStart& start() const;
  void setVehicle(const std::string& vehicle);  ///< "MOD:NAME" (base:hatchback)
  const std::string& vehicle() const;
  void setTitle(const std::string& title);      ///< the scenario's title
  /// The sky and weather (one undo step); false, changing nothing, when
  /// checkSky refuses it.
  bool setSky(const DesignSky& sky);
  const DesignSky& sky() const;
  const std::string& title() const;

  // --- undo ---
  bool undo();
  bool redo();
  bool canUndo() const;
  bool canRedo() const;
  /// Bytes the undo and redo steps hold.
  std::size_t undoBytes() const;
  /// Oldest steps are dropped while undoBytes() exceeds the budget (the
  /// newest step is always kept, so memory is at most budget + one step).
  void setUndoBudget(std::size_t bytes);
  std::size_t undoBudget() const;
  static constexpr std::size_t kDefaultUndoBudgetBytes = std::size_t(256) << 20;

  /// Bumps on every change (edits, undo, redo): the renderer and thumbnails read it.
  std::uint64_t revision() const;
  /// Hash of heights, material layers, objects, start and car (equal
  /// documents hash equal; used by tests and to tell unsaved changes).
  std::uint64_t contentHash() const;

  // --- saving ---
  /// Folders the models' "MOD:" prefixes are looked up in (default:
  /// modSearchDirs({}): the built-in mods and the user's).
  void setModFolders(std::vector<std::string> folders);
  /// Writes <modsDir>/<modName>/ (mod.lua if missing, scenarios/<scenario>.lua,
  /// maps/<scenario>.png + sidecar + layer PNGs, designs/<scenario>.design.json),
  /// each file atomically; the files of an earlier save go to
  /// <modsDir>/<modName>/backup/ first. Nothing of an earlier save changes
  /// unless every new file was written. Errors name the file or field.
  Status saveAsMod(const std::string& modsDir, const std::string& modName, const std::string& scenario);
  /// Writes one file (default: writeFileAtomic). Tests pass one that fails
  /// to show a full disk leaves the earlier save as it was.
  using WriteFileFn = std::function<Status(const std::string& path, const void* data, std::size_t size)>;
  Status saveAsMod(const std::string& modsDir, const std::string& modName, const std::string& scenario,
                   const WriteFileFn& writeFile);

 private:
  DesignDocument();
  static DesignDocument fromParts(std::unique_ptr<terrain::Terrain> terrain, DesignMeta meta);
  template <typename Fn>
  void editMeta(Fn&& fn);
  std::vector<std::string> modFolders() const;
  struct State;
  std::unique_ptr<State> m;
};

}  // namespace tumble::app
