#pragma once
// The scenario designer as the player sees it (`tumble design`, the main
// menu's Designer): a free-fly camera over the map being designed
// (app/fly_camera.h), tools under the mouse (terrain brushes, surface
// painting, objects), Dear ImGui panels, a pause menu of its own (Escape)
// and the dialogs (New map, Save as, unsaved changes). What it edits is an
// app::DesignDocument (design_document.h: heights, layers, objects, undo,
// save as a mod); this class only turns the player's input into document
// edits and draws the document. play_command.cpp runs it in the same loop
// as the game: F5 (or Drive) saves the document as a throw-away mod and
// plays it; F5 or Back to designer returns here with nothing lost.
//
//   Tools      1 Sculpt (raise, lower, smooth, flatten, noise, ridge, ditch)
//              2 Paint (the named surfaces)   3 Objects (models, props, start, gates ...)
//   Mouse      left: apply the tool; right held: look around; on the selected
//              object's gizmo: drag the red / blue arrow to move along X / Z,
//              the yellow ring to turn, the white post's top to scale (a
//              click there without a drag still places or picks)
//   Keys       WASD move, Q/E or Ctrl/Space down/up, Shift faster, [ ] radius,
//              , . previous/next brush or palette entry, Ctrl+Z / Ctrl+Y undo / redo,
//              Ctrl+S save, Ctrl+D duplicate, Delete remove, R / Shift+R turn
//              the selection 15 degrees, + / - scale it, F5 drive, Escape menu
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/design_document.h"
#include "app/designer_gizmo.h"
#include "app/fly_camera.h"
#include "app/game_catalog.h"
#include "app/scene.h"
#include "render/renderer.h"

union SDL_Event;

namespace tumble::app {

class DesignerMode {
 public:
  enum class Tool { Sculpt, Paint, Objects };
  enum class Sculpt { Raise, Lower, Smooth, Flatten, Noise, Ridge, Ditch };
  /// One entry of the object palette.
  struct PaletteEntry {
    std::string label;  ///< shown: "rock (base)", "Box", "Vehicle start"
    PlacedKind kind = PlacedKind::Model;
    std::string asset;  ///< models: "MOD:path"; emitters: the emitter's name
    bool start = false; ///< the vehicle start (not an object: DesignDocument::setStart)
  };
  /// What the designer asks of the loop that runs it.
  struct Requests {
    bool drive = false;     ///< play the document (driveOptions)
    bool mainMenu = false;  ///< leave the designer (changes saved or dropped by the player)
    bool quit = false;
  };

  /// The renderer draws the palette's model pictures and must outlive the designer.
  DesignerMode(GameCatalog& catalog, std::vector<std::string> modDirs, render::Renderer& renderer);
  ~DesignerMode();

  /// The New map dialog (nothing else can be done until a map exists).
  void showNewMap();
  /// Opens MOD:SCENARIO, a scenario the designer saved.
  Status open(const std::string& scenarioRef);
  bool hasDocument() const { return m_doc != nullptr; }
  const DesignDocument* document() const { return m_doc.get(); }

  /// Every SDL event while the designer is shown; true: consumed.
  bool handleEvent(const SDL_Event& event, bool hudWants);
  /// One frame: camera, the tool under the mouse, the snapshot to draw.
  void update(float dt_s, render::FrameSnapshot& snap);
  /// The panels and dialogs (a HUD panel: inside the ImGui frame).
  void draw();
  Requests takeRequests();

  /// Saves the document as a throw-away mod (a temporary folder) and
  /// returns the options that play it with the chosen car from the start.
  Result<SceneOptions> driveOptions(const SceneOptions& base);
  /// Back from driving: the camera as it was.
  void resume();

  /// What the player sees, for the play report ("designer").
  nlohmann::json report() const;

 private:
  struct Pointer {
    float x_px = 0, y_px = 0;
    bool leftHeld = false, rightHeld = false;
    bool leftPressed = false, leftReleased = false;  // this frame
  };
  struct Held {
    bool w = false, a = false, s = false, d = false, q = false, e = false, space = false, ctrl = false, shift = false;
  };
  struct NewMapForm {
    int sizeIndex = 2;  // into kMapSizes
    float spacing_m = 1.0f;
    int generator = 0;  // flat, plasma, image
    int seed = 1;
    float roughness = 0.5f;
    float plasmaHeight_m = 40.0f;
    char imagePath[512] = {};
    float minHeight_m = 0, maxHeight_m = 50;  // image: the heights of black and white
    float flatHeight_m = 0;
    bool centred = true;
    float originX_m = 0, originZ_m = 0;
    std::string error;
  };
  enum class Menu { None, Pause, ConfirmLeave, SaveAs };
  enum class Leaving { MainMenu, Quit };

  void createFromForm();
  void adoptDocument(std::unique_ptr<DesignDocument> doc);
  void buildPalette();
  void keyDown(int key, bool repeat);
  void undo();
  void redo();
  void save();
  bool saveAs(const std::string& mod, const std::string& scenario);
  void leave(Leaving where);
  void applyTool(const std::optional<Eigen::Vector3f>& hit, float dt_s);
  void endStroke();
  std::optional<std::uint32_t> objectNear(const Eigen::Vector3f& point) const;
  void placeObject(const Eigen::Vector3f& point);
  /// The Objects tool's click on the ground: picks the object there (held:
  /// and starts moving it with the pointer) or places the palette's entry.
  void objectsClick(const Eigen::Vector3f& ground, bool held);
  void addObjectDrawing(render::FrameSnapshot& snap) const;
  /// The selected object's gizmo, when the Objects tool is shown.
  std::optional<GizmoFrame> gizmoFrame() const;
  void addBrushCircle(render::FrameSnapshot& snap, const Eigen::Vector3f& centre) const;
  void markDirty(const SampleRect& r);
  void fillSurface();
  void loadModels();
  /// The model of a "MOD:path" asset, loaded on first use (null if it failed:
  /// m_modelProblems says why).
  std::shared_ptr<const render::Model> modelFor(const std::string& asset);
  /// Renders the next missing palette picture (one a frame, while the
  /// Objects tool is shown).
  void makeNextThumbnail();
  Brush currentBrush() const;
  void drawToolPanel();
  void drawNewMap();
  void drawMenu();
  void drawSaveAs();
  void drawStatusBar();
  void drawSkyControls();  ///< time of day, clouds, weather: the document's sky

  GameCatalog& m_catalog;
  std::vector<std::string> m_modDirs;
  render::Renderer& m_renderer;
  std::unique_ptr<DesignDocument> m_doc;
  std::string m_mod, m_scenario;  // where Save writes; empty: Save asks (Save as)
  std::uint64_t m_savedRevision = 0;
  bool m_everSaved = false;

  FlyCamera m_camera;
  FlyInput m_look;  // mouse motion gathered between frames
  Pointer m_pointer;
  Held m_held;
  float m_ctrlHeld_s = 0;   // how long Ctrl has been held
  bool m_ctrlUsed = false;  // a shortcut was pressed while Ctrl was held
  std::optional<Eigen::Vector3f> m_hit;  // the ground under the pointer, m

  Tool m_tool = Tool::Sculpt;
  Sculpt m_sculpt = Sculpt::Raise;
  float m_radius_m = 10, m_strength_mps = 4, m_falloff = 0.7f, m_flatten_m = 0, m_lineHeight_m = 3;
  int m_surface = 0;  // into surfacePalette()
  bool m_stroking = false;
  std::optional<Eigen::Vector3f> m_lineStart;
  std::vector<PaletteEntry> m_palette;
  int m_paletteIndex = 0;
  std::optional<std::uint32_t> m_selected;
  bool m_dragging = false;
  ViewRay m_ray;          // the pointer's ray this frame
  bool m_haveRay = false;
  GizmoHandle m_gizmoHover = GizmoHandle::None;  // the handle under the pointer
  std::optional<GizmoDrag> m_gizmoDrag;           // a handle being dragged (one undo step)
  /// A press on a handle, not yet a drag: where it was, and the ground
  /// behind it (a release there is a click on the ground).
  struct GizmoPress {
    GizmoHandle handle = GizmoHandle::None;
    GizmoFrame frame;
    ViewRay ray;
    float x_px = 0, y_px = 0;
    std::optional<Eigen::Vector3f> ground;
  };
  std::optional<GizmoPress> m_gizmoPress;
  int m_nextGateOrder = 1;
  std::string m_collision = "mesh";
  int m_vehicleIndex = 0;
  /// The sky while a slider is dragged (drawn at once; the document takes
  /// it as one undo step when the slider is let go).
  std::optional<DesignSky> m_skyDrag;
  int m_placedCount = 0;
  int m_lastChunksUploaded = 0, m_lastChunksInvalidated = 0;  // the renderer's, last frame
  float m_fogDistance_m = 0;  // the fog of the last frame drawn, m (higher eye: further; 0: none)
  double m_lastTerrainUpdate_ms = 0;                           // TerrainStats::updateTime_ms, last frame
  struct ItemRect {
    std::string label;
    float x_px = 0, y_px = 0, w_px = 0, h_px = 0;
  };
  std::vector<ItemRect> m_menuLayout;

  render::TerrainSurface m_surfaceView;
  std::uint64_t m_drawnRevision = 0;  // the document revision the surface last showed
  SampleRect m_pending;                // samples changed since the surface's last revision
  bool m_fullRebuild = true;

  bool m_showNewMap = false;
  NewMapForm m_form;
  Menu m_menu = Menu::None;
  int m_menuSelected = 0;
  Leaving m_leaving = Leaving::MainMenu;
  char m_saveMod[64] = "mymap", m_saveScenario[64] = "course";
  std::string m_saveError;
  std::string m_status;
  std::string m_driveDir;  // the throw-away mods folder of Drive
  Requests m_requests;
  bool m_returnPressed = false;
  std::map<std::string, std::shared_ptr<const render::Model>> m_models;  // by asset, loaded on first draw
  mutable std::map<std::string, std::string> m_modelProblems;
  /// The palette's model pictures by asset; an empty image: it failed
  /// (m_modelProblems says why).
  std::map<std::string, render::UiImage> m_thumbnails;
  std::vector<ItemRect> m_paletteLayout;  // where the palette's rows were drawn, for the report
};

}  // namespace tumble::app
