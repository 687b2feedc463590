#include "app/designer_mode.h"

#include <SDL.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <unistd.h>

#include "app/paths.h"
#include "app/scene_sky.h"
#include "core/log.h"
#include "render/model.h"

namespace tumble::app {

namespace {

namespace fs = std::filesystem;

constexpr float kPi = 3.14159265358979f;
constexpr int kMapSizes[] = {129, 257, 513, 1025, 2049, 4097};
constexpr const char* kMapSizeNames[] = {"129 x 129", "257 x 257", "513 x 513", "1025 x 1025", "2049 x 2049",
                                         "4097 x 4097"};
constexpr const char* kGenerators[] = {"flat", "plasma", "image"};
constexpr const char* kSculptNames[] = {"Raise", "Lower", "Smooth", "Flatten", "Noise", "Ridge", "Ditch"};
constexpr int kSculptCount = 7;
constexpr float kMinRadius_m = 1, kMaxRadius_m = 200;
constexpr float kRadiusStep = 1.25f;   // [ and ] change the radius by this factor
constexpr float kYawStep_rad = kPi / 12;  // R turns the selection 15 degrees
constexpr float kScaleStep = 1.1f;     // + / -
constexpr float kPanelWidth_px = 230;
constexpr float kCtrlSinkDelay_s = 0.3f;  // Ctrl held this long alone moves the eye down
constexpr float kClickSlop_px = 6.0f;  // a press that moves less is a click, not a drag (ImGui's drag threshold)
// Fog distance / the eye's height above the ground, in the designer: ground
// seen down to about 11 degrees below the horizon (5 heights away) is less
// than a third hidden by fog (1 - exp(-(5/8)^2) = 0.32).
constexpr float kDesignerFogPerHeight = 8.0f;
// The look of the game's menus (pause_menu.cpp, main_menu.cpp).
const ImVec4 kHighlight(0.95f, 0.62f, 0.12f, 1.0f);
const ImVec4 kItemColor(0.18f, 0.20f, 0.24f, 0.95f);
const ImVec4 kItemHover(0.30f, 0.34f, 0.40f, 1.0f);

const char* toolName(DesignerMode::Tool t) {
  switch (t) {
    case DesignerMode::Tool::Sculpt: return "sculpt";
    case DesignerMode::Tool::Paint: return "paint";
    case DesignerMode::Tool::Objects: return "objects";
  }
  return "?";
}

Vec3 toVec3(const Eigen::Vector3f& v) { return Vec3(Real(v.x()), Real(v.y()), Real(v.z())); }
Eigen::Vector3f toFloat(const Vec3& v) { return Eigen::Vector3f(float(v.x()), float(v.y()), float(v.z())); }

bool menuButton(const char* label, bool highlighted, float width) {
  ImGui::PushStyleColor(ImGuiCol_Button, highlighted ? kHighlight : kItemColor);
  ImGui::PushStyleColor(ImGuiCol_ButtonHovered, highlighted ? kHighlight : kItemHover);
  ImGui::PushStyleColor(ImGuiCol_Text, highlighted ? ImVec4(0.08f, 0.08f, 0.08f, 1.0f) : ImVec4(1, 1, 1, 1));
  const bool pressed = ImGui::Button(label, ImVec2(width, 40));
  ImGui::PopStyleColor(3);
  return pressed;
}

std::vector<std::string> menuItems(int menu) {
  if (menu == 1) return {"Resume", "Save", "Save as", "Drive", "Main menu", "Quit"};
  if (menu == 2) return {"Save and leave", "Leave without saving", "Cancel"};
  return {};
}

}  // namespace

DesignerMode::DesignerMode(GameCatalog& catalog, std::vector<std::string> modDirs, render::Renderer& renderer)
    : m_catalog(catalog), m_modDirs(std::move(modDirs)), m_renderer(renderer) {
  buildPalette();
}

DesignerMode::~DesignerMode() {
  for (auto& [asset, image] : m_thumbnails) m_renderer.freeUiImage(image);
  if (!m_driveDir.empty()) {
    std::error_code ec;
    fs::remove_all(m_driveDir, ec);
  }
}

void DesignerMode::showNewMap() {
  m_showNewMap = true;
  m_form.error.clear();
}

void DesignerMode::buildPalette() {
  m_palette.clear();
  const std::vector<std::string> folders = modSearchDirs(m_modDirs);
  for (const std::string& asset : listModelAssets(folders)) {  // "MOD:assets/models/rock.obj"
    const auto colon = asset.find(':');
    m_palette.push_back({fs::path(asset.substr(colon + 1)).stem().string() + " (" + asset.substr(0, colon) + ")",
                         PlacedKind::Model, asset});
  }
  m_palette.push_back({"Box (prop)", PlacedKind::Box, ""});
  m_palette.push_back({"Barrel (prop)", PlacedKind::Barrel, ""});
  m_palette.push_back({"Rag-doll", PlacedKind::Ragdoll, ""});
  m_palette.push_back({"Gate", PlacedKind::Gate, ""});
  m_palette.push_back({"Trigger box", PlacedKind::Trigger, ""});
  for (const std::string& emitter : listEmitters(folders))
    m_palette.push_back({"Emitter: " + emitter, PlacedKind::Emitter, emitter});
  m_palette.push_back({"Vehicle start", PlacedKind::Model, "", true});
}

// --- documents -------------------------------------------------------------

void DesignerMode::adoptDocument(std::unique_ptr<DesignDocument> doc) {
  m_doc = std::move(doc);
  m_doc->setModFolders(modSearchDirs(m_modDirs));
  m_selected.reset();
  m_stroking = false;
  m_fullRebuild = true;
  m_pending = SampleRect{};
  m_savedRevision = m_doc->revision();
  m_placedCount = 0;
  // Over the map's centre, looking at it from a corner.
  const terrain::Terrain& t = m_doc->terrain();
  const terrain::Aabb box = t.bounds();
  const Eigen::Vector3f lo = toFloat(box.min), hi = toFloat(box.max);
  const Eigen::Vector3f centre = 0.5f * (lo + hi);
  const float extent = std::min(hi.x() - lo.x(), hi.z() - lo.z());
  const float ground = float(t.heightAt(Real(centre.x()), Real(centre.z())));
  m_camera.position_m = {centre.x(), ground + 0.15f * extent + 10, centre.z() + 0.35f * extent + 10};
  m_camera.lookAt({centre.x(), ground, centre.z()});
  m_vehicleIndex = 0;
  const auto& vehicles = m_catalog.vehiclesFor("base");
  for (std::size_t i = 0; i < vehicles.size(); ++i)
    if (vehicles[i].ref == m_doc->vehicle()) m_vehicleIndex = int(i);
}

void DesignerMode::createFromForm() {
  NewMapOptions o;
  o.size_samples = kMapSizes[m_form.sizeIndex];
  o.spacing_m = m_form.spacing_m;
  o.generator = kGenerators[m_form.generator];
  o.seed = std::uint64_t(std::max(0, m_form.seed));
  o.roughness = m_form.roughness;
  o.imagePath = m_form.imagePath;
  if (m_form.generator == 1) {
    o.minHeight_m = 0;
    o.maxHeight_m = m_form.plasmaHeight_m;
  } else if (m_form.generator == 2) {
    o.minHeight_m = m_form.minHeight_m;
    o.maxHeight_m = m_form.maxHeight_m;
  } else {  // flat: the ground's height, with room to raise and dig (the 16-bit range)
    o.flatHeight_m = m_form.flatHeight_m;
    o.minHeight_m = m_form.flatHeight_m - 100;
    o.maxHeight_m = m_form.flatHeight_m + 300;
  }
  o.centred = m_form.centred;
  o.originX_m = m_form.originX_m;
  o.originZ_m = m_form.originZ_m;
  auto created = DesignDocument::create(o);
  if (!created) {
    m_form.error = created.error();
    return;
  }
  adoptDocument(std::make_unique<DesignDocument>(std::move(*created)));
  m_mod.clear();
  m_scenario.clear();
  m_everSaved = false;
  m_showNewMap = false;
  m_status = "new map: " + std::to_string(o.size_samples) + " x " + std::to_string(o.size_samples) + " samples, " +
             std::to_string(o.spacing_m).substr(0, 4) + " m apart (" + o.generator + ")";
}

Status DesignerMode::open(const std::string& scenarioRef) {
  const auto colon = scenarioRef.find(':');
  if (colon == std::string::npos) return makeError("design: \"" + scenarioRef + "\" is not MOD:SCENARIO");
  const std::string mod = scenarioRef.substr(0, colon), scenario = scenarioRef.substr(colon + 1);
  const script::ModInfo* info = nullptr;
  for (const script::ModInfo& m : m_catalog.mods())
    if (m.name == mod) info = &m;
  if (!info) return makeError("design: no mod named \"" + mod + "\" in the mod folders");
  auto opened = DesignDocument::open(info->dir, scenario);  // what a designer's save wrote
  if (!opened) return makeError(opened.error());
  adoptDocument(std::make_unique<DesignDocument>(std::move(*opened)));
  m_showNewMap = false;
  // Save writes back only into the user's own mods (never the built-in ones).
  const std::string user = userModsDir();
  std::error_code ec;
  if (!user.empty() && fs::equivalent(fs::path(info->dir).parent_path(), user, ec)) {
    m_mod = mod;
    m_scenario = scenario;
    m_everSaved = true;
  }
  std::snprintf(m_saveMod, sizeof m_saveMod, "%s", mod.c_str());
  std::snprintf(m_saveScenario, sizeof m_saveScenario, "%s", scenario.c_str());
  m_status = "opened " + scenarioRef;
  return Ok{};
}

bool DesignerMode::saveAs(const std::string& mod, const std::string& scenario) {
  const std::string dir = userModsDir();
  if (dir.empty()) {
    m_saveError = "cannot save: HOME is not set (the mods folder is ~/.local/share/tumble/mods)";
    return false;
  }
  if (Status st = m_doc->saveAsMod(dir, mod, scenario); !st) {
    m_saveError = st.error();
    m_status = "not saved: " + st.error();
    return false;
  }
  m_mod = mod;
  m_scenario = scenario;
  m_everSaved = true;
  m_savedRevision = m_doc->revision();
  m_saveError.clear();
  m_status = "saved " + mod + ":" + scenario + " in " + (fs::path(dir) / mod).string();
  return true;
}

void DesignerMode::save() {
  if (!m_doc) return;
  if (m_mod.empty()) {
    m_menu = Menu::SaveAs;
    return;
  }
  saveAs(m_mod, m_scenario);
}

void DesignerMode::leave(Leaving where) {
  if (m_doc && m_doc->revision() != m_savedRevision) {
    m_leaving = where;
    m_menu = Menu::ConfirmLeave;
    m_menuSelected = 0;
    return;
  }
  if (where == Leaving::Quit) m_requests.quit = true;
  else m_requests.mainMenu = true;
  m_menu = Menu::None;
}

Result<SceneOptions> DesignerMode::driveOptions(const SceneOptions& base) {
  if (!m_doc) return makeError("drive: make a map first");
  if (m_driveDir.empty()) {
    std::error_code ec;
    const fs::path dir = fs::temp_directory_path(ec) / ("tumble-design-" + std::to_string(::getpid()));
    fs::create_directories(dir, ec);
    if (ec) return makeError("drive: cannot make " + dir.string() + ": " + ec.message());
    m_driveDir = dir.string();
  }
  const std::string mod = "designer_drive", scenario = "drive";
  if (Status st = m_doc->saveAsMod(m_driveDir, mod, scenario); !st) return makeError("drive: " + st.error());
  SceneOptions o = base;
  o.scenarioRef = mod + ":" + scenario;
  if (std::find(o.modDirs.begin(), o.modDirs.end(), m_driveDir) == o.modDirs.end()) o.modDirs.push_back(m_driveDir);
  if (!m_doc->vehicle().empty()) o.sets[kVehicleParam] = m_doc->vehicle();
  return o;
}

void DesignerMode::resume() {
  m_camera.apply(m_renderer.camera());
  m_fullRebuild = true;  // the game's scene drew another terrain meanwhile
  m_held = Held{};
  m_pointer.leftHeld = m_pointer.rightHeld = false;
  m_menu = Menu::None;
}

// --- input -----------------------------------------------------------------

bool DesignerMode::handleEvent(const SDL_Event& e, bool hudWants) {
  switch (e.type) {
    case SDL_KEYDOWN:
    case SDL_KEYUP: {
      const bool down = e.type == SDL_KEYDOWN;
      const SDL_Keycode k = e.key.keysym.sym;
      switch (k) {  // held keys: always tracked, so nothing stays held
        case SDLK_w: m_held.w = down; break;
        case SDLK_a: m_held.a = down; break;
        case SDLK_s: m_held.s = down; break;
        case SDLK_d: m_held.d = down; break;
        case SDLK_q: m_held.q = down; break;
        case SDLK_e: m_held.e = down; break;
        case SDLK_SPACE: m_held.space = down; break;
        case SDLK_LCTRL:
        case SDLK_RCTRL: m_held.ctrl = down; break;
        case SDLK_LSHIFT:
        case SDLK_RSHIFT: m_held.shift = down; break;
        default: break;
      }
      if (down && !(hudWants && k != SDLK_ESCAPE && k != SDLK_RETURN)) keyDown(int(k), e.key.repeat != 0);
      return true;
    }
    case SDL_MOUSEMOTION:
      m_pointer.x_px = float(e.motion.x);
      m_pointer.y_px = float(e.motion.y);
      if (m_pointer.rightHeld) {
        m_look.lookDx_px += float(e.motion.xrel);
        m_look.lookDy_px += float(e.motion.yrel);
      }
      return true;
    case SDL_MOUSEBUTTONDOWN:
      m_pointer.x_px = float(e.button.x);
      m_pointer.y_px = float(e.button.y);
      if (e.button.button == SDL_BUTTON_RIGHT) m_pointer.rightHeld = true;
      if (e.button.button == SDL_BUTTON_LEFT && !hudWants && m_menu == Menu::None && !m_showNewMap) {
        m_pointer.leftHeld = true;
        m_pointer.leftPressed = true;
      }
      return true;
    case SDL_MOUSEBUTTONUP:
      if (e.button.button == SDL_BUTTON_RIGHT) m_pointer.rightHeld = false;
      if (e.button.button == SDL_BUTTON_LEFT && m_pointer.leftHeld) {
        m_pointer.leftHeld = false;
        m_pointer.leftReleased = true;
      }
      return true;
    case SDL_MOUSEWHEEL:
      if (!hudWants) m_radius_m = std::clamp(m_radius_m * std::pow(kRadiusStep, float(e.wheel.y)), kMinRadius_m, kMaxRadius_m);
      return true;
    default: return false;  // quit, window events: the renderer's
  }
}

void DesignerMode::keyDown(int key, bool repeat) {
  // Dialogs and menus first: they take Return, Escape and the arrows.
  if (m_showNewMap) {
    if (key == SDLK_RETURN || key == SDLK_KP_ENTER) createFromForm();
    else if (key == SDLK_ESCAPE) {
      if (m_doc) m_showNewMap = false;
      else m_requests.mainMenu = true;  // nothing to design: back to where the player came from
    }
    return;
  }
  if (m_menu == Menu::SaveAs) {
    if (key == SDLK_RETURN || key == SDLK_KP_ENTER) {
      if (saveAs(m_saveMod, m_saveScenario)) m_menu = Menu::None;
    } else if (key == SDLK_ESCAPE) {
      m_menu = Menu::Pause;
    }
    return;
  }
  if (m_menu == Menu::Pause || m_menu == Menu::ConfirmLeave) {
    const int n = int(menuItems(m_menu == Menu::Pause ? 1 : 2).size());
    if (key == SDLK_UP) m_menuSelected = (m_menuSelected + n - 1) % n;
    else if (key == SDLK_DOWN) m_menuSelected = (m_menuSelected + 1) % n;
    else if (key == SDLK_ESCAPE) m_menu = m_menu == Menu::Pause ? Menu::None : Menu::Pause;
    else if (key == SDLK_RETURN || key == SDLK_KP_ENTER) m_returnPressed = true;  // drawMenu acts on it
    return;
  }
  if (repeat && key != SDLK_LEFTBRACKET && key != SDLK_RIGHTBRACKET) return;
  const bool ctrl = m_held.ctrl;
  if (ctrl && key != SDLK_LCTRL && key != SDLK_RCTRL) m_ctrlUsed = true;
  switch (key) {
    case SDLK_ESCAPE:
      m_menu = Menu::Pause;
      m_menuSelected = 0;
      break;
    case SDLK_F5:
      if (m_doc) m_requests.drive = true;
      break;
    case SDLK_z:
      if (ctrl) m_held.shift ? redo() : undo();
      break;
    case SDLK_y:
      if (ctrl) redo();
      break;
    case SDLK_s:
      if (ctrl) save();
      break;
    case SDLK_d:
      if (ctrl && m_doc && m_selected) {
        if (const std::uint32_t copy = m_doc->duplicateObject(*m_selected)) {
          m_selected = copy;
          m_status = "duplicated";
        }
      }
      break;
    case SDLK_DELETE:
      if (m_doc && m_selected) {
        m_doc->removeObject(*m_selected);
        m_selected.reset();
        m_status = "deleted";
      }
      break;
    case SDLK_1: m_tool = Tool::Sculpt; break;
    case SDLK_2: m_tool = Tool::Paint; break;
    case SDLK_3: m_tool = Tool::Objects; break;
    case SDLK_LEFTBRACKET: m_radius_m = std::max(kMinRadius_m, m_radius_m / kRadiusStep); break;
    case SDLK_RIGHTBRACKET: m_radius_m = std::min(kMaxRadius_m, m_radius_m * kRadiusStep); break;
    case SDLK_COMMA:
    case SDLK_PERIOD: {
      const int step = key == SDLK_PERIOD ? 1 : -1;
      if (m_tool == Tool::Sculpt) m_sculpt = Sculpt((int(m_sculpt) + step + kSculptCount) % kSculptCount);
      else if (m_tool == Tool::Paint) {
        const int n = int(surfacePalette().size());
        m_surface = (m_surface + step + n) % n;
      } else {
        const int n = int(m_palette.size());
        m_paletteIndex = (m_paletteIndex + step + n) % n;
      }
      break;
    }
    case SDLK_r:
      if (m_doc && m_selected) {
        PlacedObject o = m_doc->objects().at(*m_selected);
        o.yaw_rad += m_held.shift ? -kYawStep_rad : kYawStep_rad;
        m_doc->moveObject(*m_selected, o);
      }
      break;
    case SDLK_EQUALS:
    case SDLK_PLUS:
    case SDLK_KP_PLUS:
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
      if (m_doc && m_selected) {
        PlacedObject o = m_doc->objects().at(*m_selected);
        const bool bigger = key == SDLK_EQUALS || key == SDLK_PLUS || key == SDLK_KP_PLUS;
        o.scale *= Real(bigger ? kScaleStep : 1.0f / kScaleStep);
        m_doc->moveObject(*m_selected, o);
      }
      break;
    default: break;
  }
}

void DesignerMode::undo() {
  if (!m_doc) return;
  endStroke();
  m_status = m_doc->undo() ? "undone" : "nothing to undo";  // takeChangedSamples says what to redraw
  if (m_selected && !m_doc->objects().count(*m_selected)) m_selected.reset();
}

void DesignerMode::redo() {
  if (!m_doc) return;
  endStroke();
  m_status = m_doc->redo() ? "redone" : "nothing to redo";
  if (m_selected && !m_doc->objects().count(*m_selected)) m_selected.reset();
}

DesignerMode::Requests DesignerMode::takeRequests() {
  Requests r = m_requests;
  m_requests = Requests{};
  return r;
}

// --- the frame ---------------------------------------------------------------

Brush DesignerMode::currentBrush() const {
  Brush b;
  switch (m_sculpt) {
    case Sculpt::Lower: b.kind = BrushKind::Lower; break;
    case Sculpt::Smooth: b.kind = BrushKind::Smooth; break;
    case Sculpt::Flatten: b.kind = BrushKind::Flatten; break;
    case Sculpt::Noise: b.kind = BrushKind::Noise; break;
    default: b.kind = BrushKind::Raise; break;
  }
  b.radius_m = m_radius_m;
  b.strength_m_per_s = m_strength_mps;
  b.falloff = m_falloff;
  b.flattenHeight_m = m_flatten_m;
  b.seed = 1;
  return b;
}

void DesignerMode::markDirty(const SampleRect& r) { m_pending.include(r); }

void DesignerMode::endStroke() {
  if (m_stroking && m_doc) m_doc->endStroke();
  m_stroking = false;
}

std::optional<std::uint32_t> DesignerMode::objectNear(const Eigen::Vector3f& p) const {
  std::optional<std::uint32_t> best;
  double bestD = 1e30;
  for (const auto& [id, o] : m_doc->objects()) {
    const double reach = std::max(2.0, 1.5 * double(o.scale.maxCoeff()));
    const double d = std::hypot(double(o.position_m.x()) - p.x(), double(o.position_m.z()) - p.z());
    if (d < reach && d < bestD) {
      best = id;
      bestD = d;
    }
  }
  return best;
}

void DesignerMode::placeObject(const Eigen::Vector3f& p) {
  const PaletteEntry& entry = m_palette[std::size_t(m_paletteIndex)];
  if (entry.start) {
    m_doc->setStart(toVec3(p), double(m_camera.yaw_rad));
    m_status = "vehicle start set";
    return;
  }
  PlacedObject o;
  o.kind = entry.kind;
  o.asset = entry.asset;
  o.position_m = toVec3(p);
  o.yaw_rad = double(m_camera.yaw_rad);  // faces away from the eye, as the player looks
  // Sizes (DesignDocument's PlacedObject::scale): a 1 m box, a 0.6 m x 0.9 m
  // barrel, an 8 m wide gate with 3 m posts, a 4 x 3 x 4 m trigger.
  switch (entry.kind) {
    case PlacedKind::Barrel: o.scale = Vec3(0.6, 0.9, 0.6); break;
    case PlacedKind::Gate: o.scale = Vec3(8, 3, 1); break;
    case PlacedKind::Trigger: o.scale = Vec3(4, 3, 4); break;
    default: o.scale = Vec3::Ones(); break;
  }
  o.collision = entry.kind == PlacedKind::Model ? m_collision : "box";
  if (entry.kind == PlacedKind::Gate) {
    int last = 0;
    for (const auto& [id, other] : m_doc->objects())
      if (other.kind == PlacedKind::Gate) last = std::max(last, other.order);
    o.order = last + 1;  // the next gate of the lap
  }
  const std::uint32_t id = m_doc->addObject(o);
  if (id == 0) {
    m_status = "cannot place " + entry.label + " here";
    return;
  }
  m_selected = id;
  ++m_placedCount;
  m_status = "placed " + entry.label;
}

void DesignerMode::applyTool(const std::optional<Eigen::Vector3f>& hit, float dt_s) {
  const bool line = m_tool == Tool::Sculpt && (m_sculpt == Sculpt::Ridge || m_sculpt == Sculpt::Ditch);
  // A press on a gizmo handle drags it once the pointer has moved
  // kClickSlop_px; let go before that, it is a click on what lies behind
  // (placing the next tree beside the last one, whose handles are there).
  // The handle is picked at the press itself: a press reaches the designer
  // only off the panel (the HUD takes those on it), wherever the pointer
  // was at the last frame.
  if (m_pointer.leftPressed && m_haveRay)
    if (const auto frame = gizmoFrame())
      if (const GizmoHandle handle = pickGizmoHandle(*frame, m_ray); handle != GizmoHandle::None) {
        m_pointer.leftPressed = false;
        m_gizmoPress = GizmoPress{handle, *frame, m_ray, m_pointer.x_px, m_pointer.y_px, hit};
      }
  if (m_gizmoPress && !m_gizmoDrag && m_pointer.leftHeld && m_selected && m_doc->objects().count(*m_selected) &&
      std::hypot(m_pointer.x_px - m_gizmoPress->x_px, m_pointer.y_px - m_gizmoPress->y_px) >= kClickSlop_px) {
    if (auto drag = beginGizmoDrag(m_gizmoPress->handle, m_gizmoPress->frame, m_doc->objects().at(*m_selected),
                                   m_gizmoPress->ray)) {
      m_gizmoDrag = drag;
      m_doc->beginStroke();
      m_stroking = true;
    } else {
      m_gizmoPress.reset();  // seen edge-on: nothing to drag on
    }
  }
  if (m_gizmoDrag && m_pointer.leftHeld && m_selected && m_doc->objects().count(*m_selected) && m_haveRay) {
    const PlacedObject moved = dragGizmo(*m_gizmoDrag, m_ray);
    if (!(moved == m_doc->objects().at(*m_selected)) && !m_doc->moveObject(*m_selected, moved))
      m_status = "cannot move the object there";
  }
  if (m_pointer.leftPressed) {
    m_pointer.leftPressed = false;
    if (hit && m_tool == Tool::Objects) {
      objectsClick(*hit, true);
    } else if (hit && line) {
      m_lineStart = hit;
    } else if (hit) {
      m_doc->beginStroke();
      m_stroking = true;
    }
  }
  if (m_pointer.leftHeld && hit && m_stroking) {
    if (m_tool == Tool::Sculpt && !line) {
      markDirty(m_doc->dab(currentBrush(), double(hit->x()), double(hit->z()), double(dt_s)));
    } else if (m_tool == Tool::Paint) {
      const auto& palette = surfacePalette();
      markDirty(m_doc->paint(palette[std::size_t(m_surface) % palette.size()], double(hit->x()), double(hit->z()),
                             double(m_radius_m)));
    } else if (m_tool == Tool::Objects && m_dragging && m_selected && m_doc->objects().count(*m_selected)) {
      PlacedObject o = m_doc->objects().at(*m_selected);
      o.position_m = toVec3(*hit);
      m_doc->moveObject(*m_selected, o);
    }
  }
  if (m_pointer.leftReleased) {
    m_pointer.leftReleased = false;
    if (line && m_lineStart && hit) {
      m_doc->beginStroke();
      markDirty(m_doc->line(m_sculpt == Sculpt::Ridge, Vec2(Real(m_lineStart->x()), Real(m_lineStart->z())),
                            Vec2(Real(hit->x()), Real(hit->z())), double(m_radius_m), double(m_lineHeight_m)));
      m_doc->endStroke();
      m_status = std::string(m_sculpt == Sculpt::Ridge ? "ridge" : "ditch") + " drawn";
    }
    m_lineStart.reset();
    m_dragging = false;
    if (m_gizmoDrag) m_status = std::string(gizmoHandleName(m_gizmoDrag->handle)) + " done";
    else if (m_gizmoPress && m_gizmoPress->ground) objectsClick(*m_gizmoPress->ground, false);
    m_gizmoDrag.reset();
    m_gizmoPress.reset();
    endStroke();
  }
}

void DesignerMode::objectsClick(const Eigen::Vector3f& ground, bool held) {
  if (auto near = objectNear(ground); near && !m_palette[std::size_t(m_paletteIndex)].start) {
    m_selected = near;  // a click on an object picks it; dragging then moves it
    if (held) {
      m_dragging = true;
      m_doc->beginStroke();
      m_stroking = true;
    }
  } else {
    placeObject(ground);
  }
}

// The renderer's view of the document's terrain. The document says which
// samples changed since the last frame (edits, undo, redo); the renderer
// then rebuilds only the chunks they touch.
void DesignerMode::fillSurface() {
  render::TerrainSurface& s = m_surfaceView;
  const std::uint64_t shown = s.revision;
  m_doc->fillSurface(s);  // pointers, sizes; its revision is the document's
  s.revision = shown;     // ours counts what the renderer was handed
  m_pending.include(m_doc->takeChangedSamples());
  if (m_fullRebuild) {
    s.dirtySinceRevision = 0;
    s.dirtyI1 = s.dirtyJ1 = -1;
    s.revision += 2;  // never the revision a dirty rectangle could name
    m_fullRebuild = false;
    m_pending = SampleRect{};
  } else if (!m_pending.empty()) {
    s.dirtySinceRevision = s.revision;
    ++s.revision;
    s.dirtyI0 = m_pending.i0;
    s.dirtyJ0 = m_pending.j0;
    s.dirtyI1 = m_pending.i1;
    s.dirtyJ1 = m_pending.j1;
    m_pending = SampleRect{};
  }
  m_drawnRevision = m_doc->revision();
}

void DesignerMode::update(float dt_s, render::FrameSnapshot& snap) {
  snap = render::FrameSnapshot{};
  // The camera: keys held, mouse motion with the right button.
  FlyInput in = m_look;
  m_look = FlyInput{};
  const bool typing = ImGui::GetCurrentContext() && ImGui::GetIO().WantTextInput;
  if (m_menu == Menu::None && !m_showNewMap && !typing) {
    // Ctrl is also the shortcuts' modifier: with it held the letters do not
    // move the eye (Ctrl+S, Ctrl+D), and Ctrl itself sinks the eye only once
    // held kCtrlSinkDelay_s with no shortcut, so Ctrl+Z does not move the view.
    const bool letters = !m_held.ctrl;
    m_ctrlHeld_s = m_held.ctrl ? m_ctrlHeld_s + dt_s : 0.0f;
    if (!m_held.ctrl) m_ctrlUsed = false;
    in.forward = letters && m_held.w;
    in.back = letters && m_held.s;
    in.left = letters && m_held.a;
    in.right = letters && m_held.d;
    in.up = letters && (m_held.e || m_held.space);
    in.down = (letters && m_held.q) || (m_held.ctrl && !m_ctrlUsed && m_ctrlHeld_s >= kCtrlSinkDelay_s);
    in.fast = m_held.shift;
  }
  m_camera.update(in, dt_s);
  m_camera.apply(m_renderer.camera());
  if (!m_doc) return;

  // The ground under the pointer.
  int w = 0, h = 0;
  if (SDL_Window* window = SDL_GetWindowFromID(m_renderer.windowId())) SDL_GetWindowSize(window, &w, &h);
  m_hit.reset();
  if (w > 0 && h > 0) {
    const float x = 2.0f * m_pointer.x_px / float(w) - 1.0f, y = 1.0f - 2.0f * m_pointer.y_px / float(h);
    const auto [origin, direction] = m_renderer.viewRay(x, y);
    m_ray = ViewRay{origin, direction};
    m_haveRay = true;
    if (auto hit = m_doc->terrain().rayCast(toVec3(origin), toVec3(direction), Real(1e5)))
      m_hit = toFloat(hit->point);
  }
  // The handle under the pointer (held while one is dragged). Over the panel
  // the pointer belongs to the panel.
  const bool overPanel = ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse;
  if (!m_gizmoDrag) {
    const auto frame = gizmoFrame();
    m_gizmoHover = frame && m_haveRay && !overPanel ? pickGizmoHandle(*frame, m_ray) : GizmoHandle::None;
  }
  if (m_menu == Menu::None && !m_showNewMap) applyTool(m_hit, dt_s);
  // Keep the camera above the ground it flies over.
  const Vec3 eye = toVec3(m_camera.position_m);
  if (m_doc->terrain().contains(eye.x(), eye.z())) {
    const float ground = float(m_doc->terrain().heightAt(eye.x(), eye.z()));
    m_camera.position_m.y() = std::max(m_camera.position_m.y(), ground + 1.0f);
  }

  loadModels();
  if (m_tool == Tool::Objects) makeNextThumbnail();
  fillSurface();
  snap.terrain = &m_surfaceView;
  // The sky the saved scenario will set (environment.set), so the designer
  // shows the light and weather the course is played in.
  const DesignSky& sky = m_skyDrag ? *m_skyDrag : m_doc->sky();
  script::EnvironmentRequest environment;
  environment.timeOfDay_h = sky.timeOfDay_h;
  environment.weather = sky.weather;
  environment.cloudCover = sky.cloudCover;
  snap.sky = skySettingsOf(environment);
  // The designer looks down on the whole map: from high up the course's
  // fog (250 m on a clear day) would hide most of it. The fog there starts
  // further out, kDesignerFogPerHeight times the eye's height above the
  // ground; near the ground, and when driving, it is the course's own.
  const float weatherFog_m = snap.sky.fogDistance_m.value_or(render::weatherFogDistance_m(snap.sky.weather));
  if (weatherFog_m > 0) {
    const float above_m = m_camera.position_m.y() - float(m_doc->groundHeight_m(double(m_camera.position_m.x()),
                                                                                 double(m_camera.position_m.z())));
    snap.sky.fogDistance_m = std::max(weatherFog_m, kDesignerFogPerHeight * above_m);
  }
  m_fogDistance_m = snap.sky.fogDistance_m.value_or(0.0f);
  addObjectDrawing(snap);
  if (m_gizmoDrag) {
    addGizmoLines(m_gizmoDrag->frame, m_gizmoDrag->handle, snap.lines);
  } else if (const auto frame = gizmoFrame()) {
    addGizmoLines(*frame, m_gizmoHover, snap.lines);
  }
  if (m_hit && m_menu == Menu::None && m_gizmoHover == GizmoHandle::None && !m_gizmoDrag) addBrushCircle(snap, *m_hit);
  const render::TerrainStats& stats = m_renderer.terrainStats();
  m_lastChunksUploaded = stats.chunksUploaded;
  m_lastChunksInvalidated = stats.chunksInvalidated;
  m_lastTerrainUpdate_ms = stats.updateTime_ms;
}

std::optional<GizmoFrame> DesignerMode::gizmoFrame() const {
  if (!m_doc || m_tool != Tool::Objects || m_menu != Menu::None || !m_selected) return std::nullopt;
  auto it = m_doc->objects().find(*m_selected);
  if (it == m_doc->objects().end()) return std::nullopt;
  return gizmoFrameFor(it->second, m_camera.position_m);
}

void DesignerMode::addBrushCircle(render::FrameSnapshot& snap, const Eigen::Vector3f& c) const {
  const terrain::Terrain& t = m_doc->terrain();
  const float radius = m_tool == Tool::Objects ? 1.0f : m_radius_m;
  const Eigen::Vector3f colour = m_tool == Tool::Paint ? Eigen::Vector3f(0.3f, 0.8f, 1.0f) : Eigen::Vector3f(1, 0.6f, 0.1f);
  constexpr int kSegments = 48;
  auto ground = [&](float x, float z) {
    const float y = t.contains(x, z) ? float(t.heightAt(x, z)) : c.y();
    return Eigen::Vector3f(x, y + 0.15f, z);
  };
  for (int k = 0; k < kSegments; ++k) {
    const float a0 = 2 * kPi * float(k) / kSegments, a1 = 2 * kPi * float(k + 1) / kSegments;
    snap.lines.push_back({ground(c.x() + radius * std::cos(a0), c.z() + radius * std::sin(a0)),
                          ground(c.x() + radius * std::cos(a1), c.z() + radius * std::sin(a1)), colour});
  }
  snap.lines.push_back({c, c + Eigen::Vector3f(0, 2, 0), colour});
  if (m_lineStart) snap.lines.push_back({*m_lineStart + Eigen::Vector3f(0, 0.3f, 0), c + Eigen::Vector3f(0, 0.3f, 0), colour});
}

void DesignerMode::addObjectDrawing(render::FrameSnapshot& snap) const {
  auto wireBox = [&](const Eigen::Vector3f& centre, const Eigen::Vector3f& half, const Eigen::Quaternionf& q,
                     const Eigen::Vector3f& colour) {
    Eigen::Vector3f p[8];
    for (int k = 0; k < 8; ++k)
      p[k] = centre + q * Eigen::Vector3f((k & 1 ? 1 : -1) * half.x(), (k & 2 ? 1 : -1) * half.y(), (k & 4 ? 1 : -1) * half.z());
    const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& e : edges) snap.lines.push_back({p[e[0]], p[e[1]], colour});
  };
  for (const auto& [id, o] : m_doc->objects()) {
    const Eigen::Vector3f pos = toFloat(o.position_m), scale = toFloat(o.scale);
    const Eigen::Quaternionf q(Eigen::AngleAxisf(float(o.yaw_rad), Eigen::Vector3f::UnitY()));
    const bool selected = m_selected && *m_selected == id;
    render::DrawShape s;
    s.orientation = q;
    switch (o.kind) {
      case PlacedKind::Model: {
        auto it = m_models.find(o.asset);
        if (it != m_models.end() && it->second) {
          render::ModelInstance m;
          m.model = it->second;
          m.position = pos;
          m.orientation = q;
          m.scale = scale;
          if (selected) m.tint = {1.4f, 1.2f, 0.7f};
          snap.models.push_back(m);
        } else {
          s.kind = render::ShapeKind::Box;
          s.halfExtents = 0.5f * scale;
          s.position = pos + Eigen::Vector3f(0, 0.5f * scale.y(), 0);
          s.color = {0.6f, 0.3f, 0.6f};
          snap.shapes.push_back(s);
        }
        break;
      }
      case PlacedKind::Box:
        s.kind = render::ShapeKind::Box;
        s.halfExtents = 0.5f * scale;
        s.position = pos + Eigen::Vector3f(0, 0.5f * scale.y(), 0);
        s.color = {0.7f, 0.5f, 0.25f};
        snap.shapes.push_back(s);
        break;
      case PlacedKind::Barrel:  // scale: diameter, height
        s.kind = render::ShapeKind::Capsule;
        s.radius_m = 0.5f * scale.x();
        s.halfHeight_m = std::max(0.0f, 0.5f * scale.y() - s.radius_m);
        s.position = pos + Eigen::Vector3f(0, s.radius_m + s.halfHeight_m, 0);
        s.color = {0.2f, 0.35f, 0.7f};
        snap.shapes.push_back(s);
        break;
      case PlacedKind::Ragdoll:  // scale.x: 1 = a 1.8 m adult
        s.kind = render::ShapeKind::Capsule;
        s.radius_m = 0.2f * scale.x();
        s.halfHeight_m = 0.7f * scale.x();
        s.position = pos + Eigen::Vector3f(0, s.radius_m + s.halfHeight_m, 0);
        s.color = {0.9f, 0.75f, 0.6f};
        snap.shapes.push_back(s);
        break;
      case PlacedKind::Gate: {  // scale: width between the posts, post height; the order as bars on a post
        const Eigen::Vector3f across = q * Eigen::Vector3f(0.5f * scale.x(), 0, 0);
        const float h = scale.y();
        for (float side : {-1.0f, 1.0f}) {
          s.kind = render::ShapeKind::Box;
          s.halfExtents = {0.15f, 0.5f * h, 0.15f};
          s.position = pos + side * across + Eigen::Vector3f(0, 0.5f * h, 0);
          s.color = {0.95f, 0.55f, 0.1f};
          snap.shapes.push_back(s);
        }
        snap.lines.push_back({pos - across + Eigen::Vector3f(0, h, 0), pos + across + Eigen::Vector3f(0, h, 0), {1, 1, 1}});
        for (int k = 0; k < o.order; ++k) {
          const Eigen::Vector3f a = pos - across + Eigen::Vector3f(0, h + 0.3f + 0.2f * float(k), 0);
          snap.lines.push_back({a, a + q * Eigen::Vector3f(0.6f, 0, 0), {1, 1, 0}});
        }
        break;
      }
      case PlacedKind::Trigger:  // scale: full size
        wireBox(pos + Eigen::Vector3f(0, 0.5f * scale.y(), 0), 0.5f * scale, q, {0.2f, 1.0f, 0.4f});
        break;
      case PlacedKind::Emitter:
        s.kind = render::ShapeKind::Sphere;
        s.radius_m = 0.4f;
        s.position = pos + Eigen::Vector3f(0, 0.4f, 0);
        s.color = o.asset == "base:fire" ? Eigen::Vector3f(1, 0.3f, 0.05f) : Eigen::Vector3f(0.6f, 0.6f, 0.65f);
        snap.shapes.push_back(s);
        break;
    }
    if (selected) {
      const float r = std::max(1.5f, 1.2f * scale.maxCoeff());
      wireBox(pos + Eigen::Vector3f(0, r, 0), Eigen::Vector3f(r, r, r), q, {1, 0.9f, 0.1f});
    }
  }
  // The vehicle start: an arrow along the heading.
  const Eigen::Vector3f p = toFloat(m_doc->start().position_m) + Eigen::Vector3f(0, 0.3f, 0);
  const float heading = float(m_doc->start().heading_rad);
  const Eigen::Vector3f f(std::sin(heading), 0, std::cos(heading)), r(-f.z(), 0, f.x());
  const Eigen::Vector3f green(0.1f, 1.0f, 0.2f);
  snap.lines.push_back({p - 2.0f * f, p + 3.0f * f, green});
  snap.lines.push_back({p + 3.0f * f, p + 1.5f * f + r, green});
  snap.lines.push_back({p + 3.0f * f, p + 1.5f * f - r, green});
  wireBox(p + Eigen::Vector3f(0, 0.7f, 0), {1.0f, 0.7f, 2.0f},
          Eigen::Quaternionf(Eigen::AngleAxisf(heading, Eigen::Vector3f::UnitY())), green);
}

// Models are loaded the first time an object shows them; a model that fails
// is drawn as a box and its problem shown in the panel.
void DesignerMode::loadModels() {
  for (const auto& [id, o] : m_doc->objects())
    if (o.kind == PlacedKind::Model) modelFor(o.asset);
}

std::shared_ptr<const render::Model> DesignerMode::modelFor(const std::string& asset) {
  if (auto it = m_models.find(asset); it != m_models.end()) return it->second;
  std::shared_ptr<const render::Model> model;
  const auto colon = asset.find(':');
  std::string file;
  if (colon != std::string::npos)
    for (const script::ModInfo& mod : m_catalog.mods())
      if (mod.name == asset.substr(0, colon)) file = (fs::path(mod.dir) / asset.substr(colon + 1)).string();
  if (file.empty()) {
    m_modelProblems[asset] = "no mod for \"" + asset + "\" (expected MOD:path)";
  } else if (auto loaded = render::loadModel(file)) {
    model = *loaded;
  } else {
    m_modelProblems[asset] = loaded.error();
    log::warn("designer: " + loaded.error());
  }
  m_models[asset] = model;
  return model;
}

// One picture a frame, so opening the Objects tool never stalls the view
// (a model loads and draws in a few ms; a hundred models take a hundred frames).
void DesignerMode::makeNextThumbnail() {
  constexpr int kThumbnail_px = 96;
  for (const PaletteEntry& e : m_palette) {
    if (e.kind != PlacedKind::Model || e.start || m_thumbnails.count(e.asset)) continue;
    render::UiImage image;
    if (auto model = modelFor(e.asset)) {
      if (auto made = m_renderer.renderModelThumbnail(model, kThumbnail_px)) {
        image = *made;
      } else {
        m_modelProblems[e.asset] = made.error();
        log::warn("designer: " + made.error());
      }
    }
    m_thumbnails[e.asset] = image;
    return;
  }
}

// --- panels ----------------------------------------------------------------

void DesignerMode::draw() {
  if (m_showNewMap) {
    drawNewMap();
    return;
  }
  if (!m_doc) return;
  drawToolPanel();
  drawStatusBar();
  if (m_menu == Menu::Pause || m_menu == Menu::ConfirmLeave) drawMenu();
  if (m_menu == Menu::SaveAs) drawSaveAs();
}

void DesignerMode::drawToolPanel() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth_px, display.y - 52), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("Designer", nullptr, flags)) {
    const char* tools[] = {"Sculpt", "Paint", "Objects"};
    for (int t = 0; t < 3; ++t) {
      if (t > 0) ImGui::SameLine();
      ImGui::PushStyleColor(ImGuiCol_Button, int(m_tool) == t ? kHighlight : kItemColor);
      ImGui::PushStyleColor(ImGuiCol_Text, int(m_tool) == t ? ImVec4(0.08f, 0.08f, 0.08f, 1) : ImVec4(1, 1, 1, 1));
      if (ImGui::Button(tools[t], ImVec2((kPanelWidth_px - 32) / 3, 28))) m_tool = Tool(t);
      ImGui::PopStyleColor(2);
    }
    ImGui::Separator();
    if (m_tool == Tool::Sculpt) {
      for (int k = 0; k < kSculptCount; ++k)
        if (ImGui::RadioButton(kSculptNames[k], int(m_sculpt) == k)) m_sculpt = Sculpt(k);
      ImGui::SliderFloat("radius m", &m_radius_m, kMinRadius_m, kMaxRadius_m, "%.1f", ImGuiSliderFlags_Logarithmic);
      if (m_sculpt == Sculpt::Ridge || m_sculpt == Sculpt::Ditch) {
        ImGui::SliderFloat("height m", &m_lineHeight_m, 0.2f, 30.0f, "%.1f");
        ImGui::TextWrapped("Drag a line on the ground.");
      } else {
        ImGui::SliderFloat("m/s", &m_strength_mps, 0.1f, 40.0f, "%.1f", ImGuiSliderFlags_Logarithmic);
        ImGui::SliderFloat("falloff", &m_falloff, 0.0f, 1.0f, "%.2f");
        if (m_sculpt == Sculpt::Flatten) {
          ImGui::SliderFloat("to m", &m_flatten_m, -50.0f, 200.0f, "%.1f");
          if (m_hit && ImGui::Button("Height under the cursor")) m_flatten_m = m_hit->y();
        }
      }
    } else if (m_tool == Tool::Paint) {
      const auto& palette = surfacePalette();
      for (int k = 0; k < int(palette.size()); ++k)
        if (ImGui::RadioButton(palette[std::size_t(k)].name.c_str(), m_surface == k)) m_surface = k;
      ImGui::SliderFloat("radius m", &m_radius_m, kMinRadius_m, kMaxRadius_m, "%.1f", ImGuiSliderFlags_Logarithmic);
    } else {
      ImGui::TextUnformatted("Click the ground to place:");
      // Models with their picture beside the name; the rest by name.
      constexpr float kPicture_px = 40;
      // A third of the window: at 720 px the panel then holds the palette,
      // the selected object's controls, the sky and the buttons without
      // scrolling.
      ImGui::BeginChild("palette", ImVec2(0, std::clamp(display.y / 3, 150.0f, 480.0f)), true);
      m_paletteLayout.clear();
      for (int k = 0; k < int(m_palette.size()); ++k) {
        const PaletteEntry& e = m_palette[std::size_t(k)];
        ImGui::PushID(k);
        const ImVec2 at = ImGui::GetCursorScreenPos();
        bool picked = false;
        if (e.kind == PlacedKind::Model && !e.start) {
          // One item per row (the picture and the name are drawn on it, not
          // items of their own), so the first click on a row takes even when
          // the pointer jumped there in the same frame.
          picked = ImGui::Selectable("##row", m_paletteIndex == k, 0, ImVec2(0, kPicture_px));
          ImDrawList* draw = ImGui::GetWindowDrawList();
          auto t = m_thumbnails.find(e.asset);
          if (t != m_thumbnails.end() && t->second.texture != 0)
            draw->AddImage(ImTextureID(t->second.texture), at, ImVec2(at.x + kPicture_px, at.y + kPicture_px));
          draw->AddText(ImVec2(at.x + kPicture_px + ImGui::GetStyle().ItemSpacing.x,
                               at.y + 0.5f * (kPicture_px - ImGui::GetTextLineHeight())),
                        ImGui::GetColorU32(ImGuiCol_Text), e.label.c_str());
        } else {
          picked = ImGui::Selectable(e.label.c_str(), m_paletteIndex == k);
        }
        const float rowHeight_px = e.kind == PlacedKind::Model && !e.start ? kPicture_px : ImGui::GetTextLineHeight();
        m_paletteLayout.push_back({e.label, at.x, at.y, ImGui::GetWindowContentRegionMax().x, rowHeight_px});
        if (picked) m_paletteIndex = k;
        ImGui::PopID();
      }
      ImGui::EndChild();
      const char* collisions[] = {"mesh", "box", "none"};
      int c = m_collision == "box" ? 1 : m_collision == "none" ? 2 : 0;
      if (ImGui::Combo("collision", &c, collisions, 3)) m_collision = collisions[c];
      if (m_selected && m_doc->objects().count(*m_selected)) {
        PlacedObject o = m_doc->objects().at(*m_selected);
        ImGui::Separator();
        ImGui::Text("Selected: %s %s", placedKindName(o.kind), o.asset.c_str());
        // Models scale by a factor; boxes, gates, triggers ... by their size in m (x; y, z keep their ratio).
        float yaw_deg = float(o.yaw_rad * 180.0 / kPi), size = float(o.scale.x());
        bool changed = ImGui::SliderFloat("yaw deg", &yaw_deg, -180, 180, "%.0f");
        changed |= ImGui::SliderFloat(o.kind == PlacedKind::Model ? "scale" : "size m", &size, 0.1f, 50.0f, "%.2f",
                                      ImGuiSliderFlags_Logarithmic);
        int ci = o.collision == "box" ? 1 : o.collision == "none" ? 2 : 0;
        changed |= ImGui::Combo("collides", &ci, collisions, 3);
        if (o.kind == PlacedKind::Gate) changed |= ImGui::InputInt("order", &o.order);
        if (changed) {
          o.yaw_rad = double(yaw_deg) * kPi / 180.0;
          if (size > 0) o.scale *= Real(double(size) / o.scale.x());
          o.collision = collisions[ci];
          m_doc->moveObject(*m_selected, o);
        }
        if (ImGui::Button("Duplicate"))
          if (const std::uint32_t copy = m_doc->duplicateObject(*m_selected)) m_selected = copy;
        ImGui::SameLine();
        if (ImGui::Button("Delete")) {
          m_doc->removeObject(*m_selected);
          m_selected.reset();
        }
        if (auto p = m_modelProblems.find(o.asset); p != m_modelProblems.end())
          ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", p->second.c_str());
      }
    }
    ImGui::Separator();
    drawSkyControls();
    const auto& vehicles = m_catalog.vehiclesFor("base");
    if (!vehicles.empty()) {
      m_vehicleIndex = std::clamp(m_vehicleIndex, 0, int(vehicles.size()) - 1);
      if (ImGui::BeginCombo("car", vehicles[std::size_t(m_vehicleIndex)].name.c_str())) {
        for (int k = 0; k < int(vehicles.size()); ++k)
          if (ImGui::Selectable(vehicles[std::size_t(k)].name.c_str(), k == m_vehicleIndex)) m_vehicleIndex = k;
        ImGui::EndCombo();
      }
      if (vehicles[std::size_t(m_vehicleIndex)].ref != m_doc->vehicle())
        m_doc->setVehicle(vehicles[std::size_t(m_vehicleIndex)].ref);
    }
    ImGui::BeginDisabled(!m_doc->canUndo());
    if (ImGui::Button("Undo")) undo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!m_doc->canRedo());
    if (ImGui::Button("Redo")) redo();
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Drive (F5)")) m_requests.drive = true;
    ImGui::TextDisabled("WASD QE move, right drag look");
    ImGui::TextDisabled("[ ] radius  , . next  Esc menu");
  }
  ImGui::End();
}

void DesignerMode::drawSkyControls() {
  DesignSky sky = m_skyDrag ? *m_skyDrag : m_doc->sky();
  float hours = float(sky.timeOfDay_h), clouds = float(sky.cloudCover);
  // Only the slider moved changes its field (the float round trip would
  // change the other by a rounding error).
  bool dragged = false, released = false;
  if (ImGui::SliderFloat("hour", &hours, 0.0f, 24.0f, "%.1f")) sky.timeOfDay_h = double(hours), dragged = true;
  released |= ImGui::IsItemDeactivatedAfterEdit();
  if (ImGui::SliderFloat("clouds", &clouds, 0.0f, 1.0f, "%.2f")) sky.cloudCover = double(clouds), dragged = true;
  released |= ImGui::IsItemDeactivatedAfterEdit();
  if (dragged) m_skyDrag = sky;
  const char* kinds[] = {"clear", "cloudy", "storm"};
  if (ImGui::BeginCombo("weather", sky.weather.c_str())) {
    for (const char* k : kinds)
      if (ImGui::Selectable(k, sky.weather == k)) {
        sky.weather = k;
        released = true;
      }
    ImGui::EndCombo();
  }
  if (released) {
    m_doc->setSky(sky);
    m_skyDrag.reset();
  }
}

void DesignerMode::drawStatusBar() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0, display.y - 36), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(display.x, 36), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.6f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##designer_status", nullptr, flags)) {
    const std::string name = m_mod.empty() ? std::string("(not saved)") : m_mod + ":" + m_scenario;
    const bool unsaved = m_doc->revision() != m_savedRevision;
    if (m_hit)
      ImGui::Text("%s%s   cursor %.1f, %.1f, %.1f m   %s", name.c_str(), unsaved ? " *" : "", m_hit->x(), m_hit->y(),
                  m_hit->z(), m_status.c_str());
    else
      ImGui::Text("%s%s   %s", name.c_str(), unsaved ? " *" : "", m_status.c_str());
  }
  ImGui::End();
}

void DesignerMode::drawNewMap() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::GetBackgroundDrawList()->AddRectFilled(ImVec2(0, 0), display, IM_COL32(0, 0, 0, 110));
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.92f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(18, 14));
  ImGui::PushStyleVar(ImGuiStyleVar_FrameRounding, 6.0f);
  if (ImGui::Begin("New map", nullptr, flags)) {
    ImGui::PushItemWidth(200);
    ImGui::Combo("size (samples)", &m_form.sizeIndex, kMapSizeNames, IM_ARRAYSIZE(kMapSizeNames));
    ImGui::SliderFloat("spacing m", &m_form.spacing_m, 0.25f, 8.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    const int n = kMapSizes[m_form.sizeIndex];
    ImGui::TextDisabled("the map is %.0f m x %.0f m", double(n - 1) * m_form.spacing_m, double(n - 1) * m_form.spacing_m);
    ImGui::Combo("generator", &m_form.generator, kGenerators, IM_ARRAYSIZE(kGenerators));
    if (m_form.generator == 1) {
      ImGui::InputInt("seed", &m_form.seed);
      ImGui::SliderFloat("roughness", &m_form.roughness, 0.05f, 1.0f, "%.2f");
      ImGui::SliderFloat("height m", &m_form.plasmaHeight_m, 1.0f, 400.0f, "%.0f");
    } else if (m_form.generator == 2) {
      ImGui::InputText("image (PNG)", m_form.imagePath, sizeof m_form.imagePath);
      ImGui::InputFloat("lowest m", &m_form.minHeight_m, 1, 10, "%.1f");
      ImGui::InputFloat("highest m", &m_form.maxHeight_m, 1, 10, "%.1f");
      ImGui::TextDisabled("the image's size sets the map's size");
    } else {
      ImGui::InputFloat("height m", &m_form.flatHeight_m, 1, 10, "%.1f");
    }
    ImGui::Checkbox("centred on the origin", &m_form.centred);
    if (!m_form.centred) {
      ImGui::InputFloat("corner x m", &m_form.originX_m, 1, 10, "%.1f");
      ImGui::InputFloat("corner z m", &m_form.originZ_m, 1, 10, "%.1f");
    }
    ImGui::PopItemWidth();
    if (!m_form.error.empty()) {
      ImGui::PushTextWrapPos(420);
      ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", m_form.error.c_str());
      ImGui::PopTextWrapPos();
    }
    if (menuButton("Create", true, 140)) createFromForm();
    ImGui::SameLine();
    if (menuButton(m_doc ? "Cancel" : "Back", false, 140)) {
      if (m_doc) m_showNewMap = false;
      else m_requests.mainMenu = true;
    }
    ImGui::TextDisabled("Enter: create   Escape: back");
  }
  ImGui::End();
  ImGui::PopStyleVar(2);
}

void DesignerMode::drawMenu() {
  const bool pause = m_menu == Menu::Pause;
  const std::vector<std::string> items = menuItems(pause ? 1 : 2);
  m_menuLayout.clear();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::GetBackgroundDrawList()->AddRectFilled(ImVec2(0, 0), display, IM_COL32(0, 0, 0, 110));
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.88f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(24, 20));
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(8, 8));
  ImGui::PushStyleVar(ImGuiStyleVar_FrameRounding, 6.0f);
  int chosen = -1;
  if (ImGui::Begin("Designer menu", nullptr, flags)) {
    ImGui::SetWindowFontScale(1.4f);
    const char* title = pause ? "DESIGNER" : "UNSAVED CHANGES";
    ImGui::SetCursorPosX((ImGui::GetWindowSize().x - ImGui::CalcTextSize(title).x) * 0.5f);
    ImGui::TextUnformatted(title);
    ImGui::Separator();
    ImGui::SetWindowFontScale(1.15f);
    for (int i = 0; i < int(items.size()); ++i) {
      const ImVec2 at = ImGui::GetCursorScreenPos();
      if (menuButton(items[std::size_t(i)].c_str(), i == m_menuSelected, 260)) chosen = i;
      const ImVec2 moved = ImGui::GetIO().MouseDelta;
      if (ImGui::IsItemHovered() && (moved.x != 0 || moved.y != 0)) m_menuSelected = i;
      m_menuLayout.push_back({items[std::size_t(i)], at.x, at.y, 260, 40});
    }
    ImGui::SetWindowFontScale(1.0f);
    ImGui::TextDisabled("Escape: back   Up/Down, Enter: choose");
  }
  ImGui::End();
  ImGui::PopStyleVar(3);
  if (m_returnPressed) chosen = m_menuSelected;
  m_returnPressed = false;
  if (chosen < 0) return;
  const std::string& item = items[std::size_t(chosen)];
  if (item == "Resume") m_menu = Menu::None;
  else if (item == "Save") {
    m_menu = Menu::None;
    save();
  } else if (item == "Save as") m_menu = Menu::SaveAs;
  else if (item == "Drive") {
    m_menu = Menu::None;
    m_requests.drive = true;
  } else if (item == "Main menu") leave(Leaving::MainMenu);
  else if (item == "Quit") leave(Leaving::Quit);
  else if (item == "Save and leave") {
    if (m_mod.empty()) {
      m_menu = Menu::SaveAs;  // then leave again
    } else if (saveAs(m_mod, m_scenario)) {
      leave(m_leaving);
    }
  } else if (item == "Leave without saving") {
    m_menu = Menu::None;
    if (m_leaving == Leaving::Quit) m_requests.quit = true;
    else m_requests.mainMenu = true;
  } else if (item == "Cancel") {
    m_menu = Menu::Pause;
  }
  m_menuSelected = 0;
}

void DesignerMode::drawSaveAs() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.92f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("Save as", nullptr, flags)) {
    ImGui::PushItemWidth(200);
    ImGui::InputText("mod", m_saveMod, sizeof m_saveMod);
    ImGui::InputText("scenario", m_saveScenario, sizeof m_saveScenario);
    ImGui::PopItemWidth();
    ImGui::TextDisabled("into %s", (fs::path(userModsDir()) / m_saveMod).string().c_str());
    if (!m_saveError.empty()) {
      ImGui::PushTextWrapPos(420);
      ImGui::TextColored(ImVec4(1, 0.4f, 0.3f, 1), "%s", m_saveError.c_str());
      ImGui::PopTextWrapPos();
    }
    if (menuButton("Save", true, 120) && saveAs(m_saveMod, m_saveScenario)) m_menu = Menu::None;
    ImGui::SameLine();
    if (menuButton("Cancel", false, 120)) m_menu = Menu::Pause;
    ImGui::TextDisabled("Enter: save   Escape: back");
  }
  ImGui::End();
}

// --- the report --------------------------------------------------------------

nlohmann::json DesignerMode::report() const {
  auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  nlohmann::json j;
  j["new_map_open"] = m_showNewMap;
  const char* menus[] = {"none", "pause", "confirm_leave", "save_as"};
  j["menu"] = {{"page", menus[int(m_menu)]}, {"selected", m_menuSelected}};
  nlohmann::json items = nlohmann::json::array();
  for (const auto& it : m_menuLayout)
    items.push_back({{"label", it.label}, {"x_px", it.x_px}, {"y_px", it.y_px}, {"w_px", it.w_px}, {"h_px", it.h_px}});
  j["menu"]["items"] = items;
  j["tool"] = toolName(m_tool);
  j["sculpt"] = kSculptNames[int(m_sculpt)];
  j["radius_m"] = m_radius_m;
  j["surface"] = surfacePalette()[std::size_t(m_surface) % surfacePalette().size()].name;
  nlohmann::json palette = nlohmann::json::array();
  for (const PaletteEntry& e : m_palette) palette.push_back(e.label);
  j["palette"] = palette;
  j["palette_selected"] = m_palette[std::size_t(m_paletteIndex)].label;
  // Where each palette row was last drawn (window pixels; rows scrolled out
  // of the list included) and whether its picture was made.
  nlohmann::json rows = nlohmann::json::array();
  for (const ItemRect& r : m_paletteLayout) {
    nlohmann::json row = {{"label", r.label}, {"x_px", r.x_px}, {"y_px", r.y_px}, {"w_px", r.w_px}, {"h_px", r.h_px}};
    for (const PaletteEntry& e : m_palette)
      if (e.label == r.label && e.kind == PlacedKind::Model && !e.start) {
        auto t = m_thumbnails.find(e.asset);
        row["picture"] = t == m_thumbnails.end() ? "pending" : t->second.texture != 0 ? "drawn" : "failed";
      }
    rows.push_back(row);
  }
  j["palette_rows"] = rows;
  // The selected object's gizmo: the handle under the pointer, the one being
  // dragged, and where each handle is in the window (pixels), to aim at.
  nlohmann::json gizmo = {{"hovered", gizmoHandleName(m_gizmoHover)},
                          {"dragging", m_gizmoDrag ? gizmoHandleName(m_gizmoDrag->handle) : "none"}};
  if (const auto frame = m_gizmoDrag ? std::optional<GizmoFrame>(m_gizmoDrag->frame) : gizmoFrame()) {
    const auto [w, h] = m_renderer.windowSize();
    nlohmann::json handles = nlohmann::json::object();
    for (GizmoHandle handle : {GizmoHandle::MoveX, GizmoHandle::MoveZ, GizmoHandle::Rotate, GizmoHandle::Scale})
      if (auto v = m_renderer.viewPoint(gizmoHandlePoint(*frame, handle)))
        handles[gizmoHandleName(handle)] = {0.5f * (v->x() + 1.0f) * float(w), 0.5f * (1.0f - v->y()) * float(h)};
    gizmo["handles_px"] = handles;
    gizmo["arm_m"] = frame->arm_m;
  } else {
    gizmo["handles_px"] = nullptr;
  }
  j["gizmo"] = gizmo;
  j["camera"] = {{"position_m", vec(toVec3(m_camera.position_m))}, {"yaw_rad", m_camera.yaw_rad},
                 {"pitch_rad", m_camera.pitch_rad}};
  j["pointer_px"] = {m_pointer.x_px, m_pointer.y_px};
  j["status"] = m_status;
  j["terrain_chunks_uploaded"] = m_lastChunksUploaded;
  j["terrain_chunks_invalidated"] = m_lastChunksInvalidated;
  j["terrain_update_ms"] = m_lastTerrainUpdate_ms;
  j["fog_distance_m"] = m_fogDistance_m;
  if (!m_doc) {
    j["document"] = nullptr;
    return j;
  }
  const terrain::Terrain& t = m_doc->terrain();
  nlohmann::json d;
  d["samples"] = {t.heights().width(), t.heights().height()};
  d["spacing_m"] = t.desc().spacing_m;
  d["revision"] = m_doc->revision();
  d["can_undo"] = m_doc->canUndo();
  d["can_redo"] = m_doc->canRedo();
  d["undo_bytes"] = m_doc->undoBytes();
  d["unsaved"] = m_doc->revision() != m_savedRevision;
  d["saved_as"] = m_mod.empty() ? nlohmann::json(nullptr) : nlohmann::json(m_mod + ":" + m_scenario);
  d["vehicle"] = m_doc->vehicle();
  d["sky"] = {{"time_of_day_h", m_doc->sky().timeOfDay_h}, {"weather", m_doc->sky().weather},
              {"clouds", m_doc->sky().cloudCover}};
  if (m_hit) {
    d["cursor_m"] = vec(toVec3(*m_hit));
    d["height_at_cursor_m"] = m_doc->groundHeight_m(double(m_hit->x()), double(m_hit->z()));
  } else {
    d["cursor_m"] = nullptr;
    d["height_at_cursor_m"] = nullptr;
  }
  nlohmann::json objects = nlohmann::json::array();
  for (const auto& [id, o] : m_doc->objects())
    objects.push_back({{"id", id}, {"kind", placedKindName(o.kind)}, {"asset", o.asset}, {"position_m", vec(o.position_m)},
                       {"yaw_rad", o.yaw_rad}, {"scale", vec(o.scale)}, {"collision", o.collision}, {"order", o.order}});
  d["objects"] = objects;
  d["selected"] = m_selected ? nlohmann::json(*m_selected) : nlohmann::json(nullptr);
  j["document"] = d;
  return j;
}

}  // namespace tumble::app
