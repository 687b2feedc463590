#include "app/main_menu.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/thumbnails.h"
#include "core/log.h"

namespace tumble::app {

namespace {

constexpr float kItemWidth_px = 420.0f, kItemHeight_px = 50.0f;
const ImVec4 kHighlight(0.95f, 0.62f, 0.12f, 1.0f);  // the keyboard / pad selection (as the pause menu)
const ImVec4 kItemColor(0.16f, 0.18f, 0.22f, 0.92f);
const ImVec4 kItemHover(0.28f, 0.32f, 0.38f, 1.0f);
const ImVec4 kDimText(0.62f, 0.64f, 0.68f, 1.0f);
constexpr double kVolumeStep = 0.05;

std::string percent(double v) { return std::to_string(int(std::lround(v * 100))) + " %"; }

}  // namespace

input::BindingSet menuBindings() {
  input::BindingSet set;
  set.contexts.push_back({"ui", 200, true});
  auto add = [&](const char* name, const char* label, std::initializer_list<const char*> texts) {
    input::ActionDef a;
    a.name = name;
    a.label = label;
    a.context = "ui";
    for (const char* t : texts)
      if (auto b = input::parseBinding(t)) a.bindings.push_back(*b);
      else log::error(std::string("menu binding ") + t + ": " + b.error());  // a programmer's mistake
    set.actions.push_back(std::move(a));
  };
  add("ui_up", "Menu: up", {"key:Up", "pad:dpup", "pad_axis:lefty-"});
  add("ui_down", "Menu: down", {"key:Down", "pad:dpdown", "pad_axis:lefty+"});
  add("ui_left", "Menu: less", {"key:Left", "pad:dpleft", "pad_axis:leftx-"});
  add("ui_right", "Menu: more", {"key:Right", "pad:dpright", "pad_axis:leftx+"});
  add("ui_select", "Menu: choose", {"key:Return", "key:Keypad Enter", "key:Space", "pad:a"});
  add("ui_back", "Menu: back", {"key:Escape", "key:Backspace", "pad:b"});
  return set;
}

MainMenu::MainMenu(GameCatalog& catalog, PlayerSettings& settings, std::string settingsPath,
                   ThumbnailCache* thumbnails)
    : m_catalog(catalog), m_settings(settings), m_settingsPath(std::move(settingsPath)), m_thumbnails(thumbnails) {}

const char* MainMenu::pageName(Page page) {
  switch (page) {
    case Page::Closed: return "closed";
    case Page::Root: return "main";
    case Page::Mods: return "mods";
    case Page::Scenarios: return "scenarios";
    case Page::Vehicles: return "vehicles";
    case Page::Settings: return "settings";
    case Page::ConfirmQuit: return "confirm_quit";
  }
  return "closed";
}

void MainMenu::openRoot() {
  m_overGame = false;
  m_history.clear();
  go(Page::Root);
}

void MainMenu::openVehicles(const std::string& scenarioRef, const std::string& drivenVehicle) {
  m_overGame = true;
  m_history.clear();
  m_scenario = scenarioRef;
  m_drivenVehicle = drivenVehicle;
  if (auto ref = script::parseScenarioRef(scenarioRef)) m_mod = ref->first;
  go(Page::Vehicles);
}

void MainMenu::openSettings() {
  m_overGame = true;
  m_history.clear();
  go(Page::Settings);
}

void MainMenu::go(Page page) {
  m_page = page;
  m_selected = 0;
  m_scrollToSelected = true;
  rebuild();
  // The vehicle picker starts on the car being driven (over a game), else
  // on the scenario's own default car.
  if (page == Page::Vehicles)
    if (const ScenarioEntry* s = m_catalog.scenario(m_scenario)) {
      const auto& vs = m_catalog.vehiclesFor(m_mod);
      const std::string& start = m_overGame && !m_drivenVehicle.empty() ? m_drivenVehicle : s->defaultVehicle;
      for (std::size_t i = 0; i < vs.size(); ++i)
        if (vs[i].ref == start) m_selected = int(i);
    }
}

void MainMenu::rebuild() {
  m_items.clear();
  switch (m_page) {
    case Page::Root: buildRoot(); break;
    case Page::Mods: buildMods(); break;
    case Page::Scenarios: buildScenarios(); break;
    case Page::Vehicles: buildVehicles(); break;
    case Page::Settings: buildSettings(); break;
    case Page::ConfirmQuit: buildConfirmQuit(); break;
    case Page::Closed: break;
  }
  m_selected = std::clamp(m_selected, 0, std::max(0, int(m_items.size()) - 1));
}

// Moves to a sub-page, remembering where to come back to.
#define TUMBLE_MENU_PUSH(page)                    \
  do {                                            \
    m_history.emplace_back(m_page, m_selected);   \
    go(page);                                     \
  } while (0)

void MainMenu::buildRoot() {
  m_items.push_back({"Play", "", Kind::Button, true, "", [this] { TUMBLE_MENU_PUSH(Page::Mods); }, nullptr});
  m_items.push_back({"Designer", "", Kind::Button, true, "", [this] {
                       m_requests.openDesigner = true;
                       close();
                     }, nullptr});
  m_items.push_back({"Settings", "", Kind::Button, true, "", [this] { TUMBLE_MENU_PUSH(Page::Settings); }, nullptr});
  m_items.push_back({"Quit", "", Kind::Button, true, "", [this] { TUMBLE_MENU_PUSH(Page::ConfirmQuit); }, nullptr});
}

void MainMenu::buildMods() {
  for (const script::ModInfo& m : m_catalog.mods()) {
    const std::string name = m.name;
    m_items.push_back({m.title.empty() ? m.name : m.title, m.name, Kind::Button, true, "",
                       [this, name] {
                         m_mod = name;
                         TUMBLE_MENU_PUSH(Page::Scenarios);
                       },
                       nullptr});
  }
  m_items.push_back({"Back", "", Kind::Button, true, "", [this] { back(); }, nullptr});
}

void MainMenu::buildScenarios() {
  for (const ScenarioEntry& s : m_catalog.scenarios(m_mod)) {
    const std::string ref = s.ref;
    const bool takesVehicle = s.takesVehicle;
    m_items.push_back({s.name, takesVehicle ? "choose a vehicle" : "", Kind::Button, s.problem.empty(),
                       s.problem.empty() ? "" : "cannot be read",
                       [this, ref, takesVehicle] {
                         m_scenario = ref;
                         if (takesVehicle) {
                           TUMBLE_MENU_PUSH(Page::Vehicles);
                         } else {
                           m_requests.startScenario = ref;
                           m_requests.vehicle.reset();
                           m_history.clear();
                           close();
                         }
                       },
                       nullptr});
  }
  m_items.push_back({"Back", "", Kind::Button, true, "", [this] { back(); }, nullptr});
}

void MainMenu::buildVehicles() {
  for (const VehicleEntry& v : m_catalog.vehiclesFor(m_mod)) {
    const std::string ref = v.ref;
    m_items.push_back({v.name, v.ref, Kind::Button, v.problem.empty(), v.problem.empty() ? "" : "cannot be read",
                       [this, ref] {
                         m_requests.startScenario = m_scenario;
                         m_requests.vehicle = ref;
                         m_history.clear();
                         m_overGame = false;
                         close();
                       },
                       nullptr});
  }
  m_items.push_back({"Back", "", Kind::Button, true, "", [this] { back(); }, nullptr});
}

void MainMenu::buildSettings() {
  const auto& sizes = offeredResolutions();
  char size[64];
  std::snprintf(size, sizeof size, "%d x %d", m_settings.width, m_settings.height);
  m_items.push_back({"Resolution", size, Kind::Choice, true, "", [this] { adjust(+1); },
                     [this, &sizes](int d) {
                       // The next offered size after (or before) the current one.
                       int at = -1;
                       for (int i = 0; i < int(sizes.size()); ++i)
                         if (sizes[std::size_t(i)].first == m_settings.width &&
                             sizes[std::size_t(i)].second == m_settings.height)
                           at = i;
                       const int n = int(sizes.size());
                       at = at < 0 ? (d > 0 ? 0 : n - 1) : ((at + d) % n + n) % n;
                       m_settings.width = sizes[std::size_t(at)].first;
                       m_settings.height = sizes[std::size_t(at)].second;
                       settingsEdited(true);
                     }});
  m_items.push_back({"Fullscreen", m_settings.fullscreen ? "on" : "off", Kind::Toggle, true, "",
                     [this] { adjust(+1); },
                     [this](int) {
                       m_settings.fullscreen = !m_settings.fullscreen;
                       settingsEdited(true);
                     }});
  m_items.push_back({"Quality", qualityName(m_settings.quality), Kind::Choice, true, "", [this] { adjust(+1); },
                     [this](int d) {
                       const int q = (int(m_settings.quality) + d + 3) % 3;
                       m_settings.quality = QualityLevel(q);
                       settingsEdited(true);
                     }});
  for (auto [label, field] : {std::pair{"Master volume", &PlayerSettings::volume_master},
                              std::pair{"Effects volume", &PlayerSettings::volume_effects},
                              std::pair{"Engine volume", &PlayerSettings::volume_engine}}) {
    m_items.push_back({label, percent(m_settings.*field), Kind::Slider, true, "", nullptr,
                       [this, field = field](int d) {
                         double& v = m_settings.*field;
                         v = std::clamp(std::round((v + d * kVolumeStep) / kVolumeStep) * kVolumeStep, 0.0, 1.0);
                         settingsEdited(false);
                       }});
    m_items.back().fraction = float(m_settings.*field);
  }
  m_items.push_back({"Key and pad bindings", "F1", Kind::Button, true, "",
                     [this] { m_requests.openBindings = true; }, nullptr});
  m_items.push_back({"Back", "", Kind::Button, true, "", [this] { back(); }, nullptr});
}

void MainMenu::buildConfirmQuit() {
  m_items.push_back({"Quit to desktop", "", Kind::Button, true, "", [this] { m_requests.quit = true; }, nullptr});
  m_items.push_back({"Cancel", "", Kind::Button, true, "", [this] { back(); }, nullptr});
}

#undef TUMBLE_MENU_PUSH

// Every change is saved at once (atomically): leaving with Escape keeps it.
void MainMenu::settingsEdited(bool applyNow) {
  if (Status st = savePlayerSettings(m_settingsPath, m_settings); !st) {
    m_status = "settings not saved: " + st.error();
    log::error(m_status);
  } else {
    m_status = "saved to " + m_settingsPath;
  }
  if (applyNow) m_requests.settingsChanged = true;
  const int keep = m_selected;
  rebuild();
  m_selected = keep;
}

void MainMenu::moveSelection(int delta) {
  if (!isOpen() || m_items.empty()) return;
  const int n = int(m_items.size());
  for (int tries = 0; tries < n; ++tries) {  // disabled items are skipped
    m_selected = ((m_selected + delta) % n + n) % n;
    if (m_items[std::size_t(m_selected)].enabled) break;
  }
  m_scrollToSelected = true;
}

void MainMenu::adjust(int delta) {
  if (!isOpen() || m_selected >= int(m_items.size())) return;
  Item& it = m_items[std::size_t(m_selected)];
  if (it.enabled && it.adjust) it.adjust(delta);
}

void MainMenu::activate() {
  if (!isOpen() || m_selected >= int(m_items.size())) return;
  const Item it = m_items[std::size_t(m_selected)];  // a copy: the action may rebuild the list
  if (!it.enabled) return;
  if (it.activate) it.activate();
  else if (it.adjust) it.adjust(+1);
}

void MainMenu::back() {
  if (!isOpen()) return;
  if (!m_history.empty()) {
    auto [page, selected] = m_history.back();
    m_history.pop_back();
    go(page);
    m_selected = std::clamp(selected, 0, std::max(0, int(m_items.size()) - 1));
    return;
  }
  if (m_overGame) {  // the page was opened from the pause menu
    m_requests.backToGame = true;
    m_overGame = false;
    close();
    return;
  }
  if (m_page == Page::Root) {  // Escape on the root asks before quitting
    m_history.emplace_back(m_page, m_selected);
    go(Page::ConfirmQuit);
  }
}

void MainMenu::onAction(const std::string& name) {
  if (name == "ui_up") moveSelection(-1);
  else if (name == "ui_down") moveSelection(+1);
  else if (name == "ui_left") adjust(-1);
  else if (name == "ui_right") adjust(+1);
  else if (name == "ui_select") activate();
  else if (name == "ui_back") back();
}

MainMenu::Requests MainMenu::takeRequests() {
  Requests r = std::move(m_requests);
  m_requests = Requests{};
  return r;
}

std::string MainMenu::selectedLabel() const {
  if (m_selected < 0 || m_selected >= int(m_items.size())) return "";
  return m_items[std::size_t(m_selected)].label;
}

std::string MainMenu::thumbnailStatus() const {
  if (m_page != Page::Scenarios || !m_thumbnails) return "";
  const auto& list = m_catalog.scenarios(m_mod);
  if (m_selected < 0 || m_selected >= int(list.size())) return "";
  return m_thumbnails->status(list[std::size_t(m_selected)]);
}

std::string MainMenu::title() const {
  switch (m_page) {
    case Page::Root: return "TUMBLE";
    case Page::Mods: return "Choose a mod";
    case Page::Scenarios: {
      for (const script::ModInfo& m : m_catalog.mods())
        if (m.name == m_mod) return m.title.empty() ? m.name : m.title;
      return m_mod;
    }
    case Page::Vehicles: return "Choose a vehicle";
    case Page::Settings: return "Settings";
    case Page::ConfirmQuit: return "Quit Tumble?";
    case Page::Closed: break;
  }
  return "";
}

// The selected scenario (title, description, thumbnail) or vehicle (figures).
void MainMenu::drawDetails(float x, float y, float w, float h) {
  if (m_selected >= int(m_items.size())) return;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  ImGui::SetNextWindowBgAlpha(0.80f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus;
  if (ImGui::Begin("##menu_details", nullptr, flags)) {
    if (m_page == Page::Scenarios) {
      const auto& list = m_catalog.scenarios(m_mod);
      if (m_selected < int(list.size())) {
        const ScenarioEntry& s = list[std::size_t(m_selected)];
        ImGui::SetWindowFontScale(1.4f);
        ImGui::TextWrapped("%s", s.title.c_str());
        ImGui::SetWindowFontScale(1.0f);
        ImGui::TextColored(kDimText, "%s", s.ref.c_str());
        if (m_thumbnails) {
          if (const Thumbnail* t = m_thumbnails->get(s)) {
            const float tw = w - 24.0f;
            ImGui::Image(ImTextureID(t->texture), ImVec2(tw, tw * float(t->height) / float(std::max(1, t->width))));
          } else {
            ImGui::TextColored(kDimText, "%s", m_thumbnails->status(s).c_str());
          }
        }
        ImGui::Spacing();
        if (!s.problem.empty()) ImGui::TextColored(ImVec4(1, 0.45f, 0.35f, 1), "%s", s.problem.c_str());
        ImGui::TextWrapped("%s", s.description.c_str());
        if (s.takesVehicle) ImGui::TextColored(kHighlight, "You choose the vehicle next.");
      }
    } else if (m_page == Page::Vehicles) {
      const auto& list = m_catalog.vehiclesFor(m_mod);
      if (const ScenarioEntry* s = m_catalog.scenario(m_scenario)) ImGui::TextColored(kDimText, "for %s", s->title.c_str());
      if (m_selected < int(list.size())) {
        const VehicleEntry& v = list[std::size_t(m_selected)];
        ImGui::SetWindowFontScale(1.6f);
        ImGui::TextUnformatted(v.name.c_str());
        ImGui::SetWindowFontScale(1.0f);
        ImGui::TextColored(kDimText, "%s", v.ref.c_str());
        ImGui::Spacing();
        if (!v.problem.empty()) {
          ImGui::TextWrapped("%s", v.problem.c_str());
        } else {
          ImGui::TextWrapped("%s", v.description.c_str());
          ImGui::Spacing();
          ImGui::SetWindowFontScale(1.25f);
          if (ImGui::BeginTable("##figures", 2)) {
            auto row = [](const char* k, const std::string& val) {
              ImGui::TableNextRow();
              ImGui::TableNextColumn();
              ImGui::TextColored(kDimText, "%s", k);
              ImGui::TableNextColumn();
              ImGui::TextUnformatted(val.c_str());
            };
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.0f kg", v.mass_kg);
            row("Mass", buf);
            std::snprintf(buf, sizeof buf, "%.0f kW (%.0f hp)", v.peakPower_kW, v.peakPower_kW / 0.7457);
            row("Peak power", buf);
            std::snprintf(buf, sizeof buf, "%.0f W/kg", v.peakPower_kW * 1000.0 / std::max(1.0, v.mass_kg));
            row("Power to mass", buf);
            row("Drive", v.drive);
            std::snprintf(buf, sizeof buf, "%.2f sideways, %.2f braking", v.grip, v.gripLongitudinal);
            row("Tyre grip (peak)", buf);
            ImGui::EndTable();
          }
          ImGui::SetWindowFontScale(1.0f);
        }
      }
    }
  }
  ImGui::End();
}

void MainMenu::draw() {
  m_layout.clear();
  if (!isOpen()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  // A dimmed backdrop: the game (or the sky) stays visible behind the menu.
  ImGui::GetBackgroundDrawList()->AddRectFilledMultiColor(ImVec2(0, 0), display, IM_COL32(8, 10, 16, 150),
                                                          IM_COL32(8, 10, 16, 150), IM_COL32(8, 10, 16, 230),
                                                          IM_COL32(8, 10, 16, 230));
  const bool details = m_page == Page::Scenarios || m_page == Page::Vehicles;
  const float itemW = std::min(kItemWidth_px, display.x * 0.42f);
  const float listX = details ? display.x * 0.5f - itemW - 12.0f : (display.x - itemW) * 0.5f;
  const float top = std::max(90.0f, display.y * 0.2f);

  // Title, large and centred.
  const ImGuiWindowFlags bare = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBackground |
                                ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::SetNextWindowPos(ImVec2(0, top * 0.25f));
  ImGui::SetNextWindowSize(ImVec2(display.x, top * 0.75f));
  if (ImGui::Begin("##menu_title", nullptr, bare)) {
    const std::string t = title();
    ImGui::SetWindowFontScale(m_page == Page::Root ? 3.2f : 2.2f);
    ImGui::SetCursorPosX((display.x - ImGui::CalcTextSize(t.c_str()).x) * 0.5f);
    ImGui::TextColored(m_page == Page::Root ? kHighlight : ImVec4(1, 1, 1, 1), "%s", t.c_str());
    ImGui::SetWindowFontScale(1.0f);
  }
  ImGui::End();

  // The items.
  const float listH = display.y - top - 60.0f;
  ImGui::SetNextWindowPos(ImVec2(listX, top));
  ImGui::SetNextWindowSize(ImVec2(itemW + 16.0f, listH));
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(8, 10));
  ImGui::PushStyleVar(ImGuiStyleVar_FrameRounding, 6.0f);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(8, 4));
  if (ImGui::Begin("##menu_items", nullptr, bare & ~ImGuiWindowFlags_NoBringToFrontOnFocus)) {
    ImGui::SetWindowFontScale(1.45f);
    for (int i = 0; i < int(m_items.size()); ++i) {
      const Item& item = m_items[std::size_t(i)];
      const bool highlighted = i == m_selected && item.enabled;
      ImGui::PushID(i);
      ImGui::PushStyleColor(ImGuiCol_Button, highlighted ? kHighlight : kItemColor);
      ImGui::PushStyleColor(ImGuiCol_ButtonHovered, highlighted ? kHighlight : kItemHover);
      ImGui::PushStyleColor(ImGuiCol_ButtonActive, kHighlight);
      ImGui::PushStyleColor(ImGuiCol_Text, highlighted ? ImVec4(0.06f, 0.06f, 0.06f, 1) : ImVec4(1, 1, 1, 1));
      ImGui::PushStyleVar(ImGuiStyleVar_ButtonTextAlign, ImVec2(item.value.empty() && item.note.empty() ? 0.5f : 0.05f, 0.5f));
      if (!item.enabled) ImGui::BeginDisabled();
      const ImVec2 at = ImGui::GetCursorScreenPos();
      const bool clicked = ImGui::Button(item.label.c_str(), ImVec2(itemW, kItemHeight_px));
      const bool hovered = ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled);
      const bool rightClicked = ImGui::IsItemClicked(ImGuiMouseButton_Right);
      // The value (or why it is greyed out) on the right of the item.
      const std::string right = item.enabled ? item.value : item.note;
      if (!right.empty()) {
        ImGui::SetWindowFontScale(1.1f);
        const ImVec2 sz = ImGui::CalcTextSize(right.c_str());
        ImGui::GetWindowDrawList()->AddText(
            ImVec2(at.x + itemW - sz.x - 14.0f, at.y + (kItemHeight_px - sz.y) * 0.5f),
            ImGui::GetColorU32(highlighted ? ImVec4(0.1f, 0.1f, 0.1f, 1) : kDimText), right.c_str());
        ImGui::SetWindowFontScale(1.45f);
      }
      if (item.fraction >= 0) {  // a slider: a bar along the bottom of the item
        const float x0 = at.x + 12.0f, x1 = at.x + itemW - 12.0f, y = at.y + kItemHeight_px - 9.0f;
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddRectFilled(ImVec2(x0, y), ImVec2(x1, y + 4.0f), IM_COL32(255, 255, 255, 50), 2.0f);
        dl->AddRectFilled(ImVec2(x0, y), ImVec2(x0 + (x1 - x0) * item.fraction, y + 4.0f),
                          highlighted ? IM_COL32(30, 30, 30, 220) : IM_COL32(242, 158, 31, 230), 2.0f);
      }
      if (!item.enabled) ImGui::EndDisabled();
      ImGui::PopStyleVar();
      ImGui::PopStyleColor(4);
      ImGui::PopID();
      if (i == m_selected && m_scrollToSelected) {
        ImGui::SetScrollHereY(0.5f);
        m_scrollToSelected = false;
      }
      m_layout.push_back({item.label, at.x, at.y, itemW, kItemHeight_px});
      if (hovered && item.enabled && (ImGui::GetIO().MouseDelta.x != 0 || ImGui::GetIO().MouseDelta.y != 0)) m_selected = i;
      if (clicked) {
        m_selected = i;
        activate();
        break;  // the list may have changed
      }
      if (rightClicked && item.adjust) {
        m_selected = i;
        adjust(-1);
        break;
      }
    }
    ImGui::SetWindowFontScale(1.0f);
  }
  ImGui::End();
  ImGui::PopStyleVar(3);

  if (details && isOpen()) drawDetails(display.x * 0.5f + 12.0f, top, std::min(520.0f, display.x * 0.5f - 36.0f), listH);

  // Hints and the last status line at the bottom.
  ImGui::SetNextWindowPos(ImVec2(0, display.y - 56.0f));
  ImGui::SetNextWindowSize(ImVec2(display.x, 56.0f));
  if (ImGui::Begin("##menu_hints", nullptr, bare)) {
    const char* hint = m_page == Page::Settings
                           ? "Up/Down: choose   Left/Right: change   Return: change   Escape: back   (pad: d-pad, A, B)"
                           : "Up/Down: choose   Return: select   Escape: back   (pad: d-pad, A, B; mouse: click)";
    ImGui::SetCursorPosX((display.x - ImGui::CalcTextSize(hint).x) * 0.5f);
    ImGui::TextColored(kDimText, "%s", hint);
    if (!m_status.empty()) {
      ImGui::SetCursorPosX(std::max(8.0f, (display.x - ImGui::CalcTextSize(m_status.c_str()).x) * 0.5f));
      ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.45f, 1), "%s", m_status.c_str());
    }
  }
  ImGui::End();
}

}  // namespace tumble::app
