#include "app/bindings_menu.h"

#include <imgui.h>

#include <algorithm>

#include "app/pause_menu.h"
#include "core/log.h"
#include "input/overrides_file.h"
#include "render/camera_rig.h"

namespace tumble::app {

BindingsMenu::BindingsMenu(input::InputSystem& input, std::string configPath)
    : m_input(input), m_path(std::move(configPath)) {
  auto loaded = input::loadOverrides(m_path);
  if (!loaded) {
    m_status = loaded.error() + " -- using the default bindings; the file is kept as it is until you press Save";
    log::warn("bindings: " + m_status);
    return;
  }
  for (const std::string& p : m_input.applyOverrides(*loaded)) log::warn("bindings: " + m_path + ": " + p);
  if (!loaded->empty()) log::info("bindings: " + std::to_string(loaded->size()) + " override(s) from " + m_path);
}

void BindingsMenu::toggle() {
  m_open = !m_open;
  if (!m_open && m_input.capturing()) m_input.cancelCapture();
  m_captureAction = -1;
  m_waitingPositive = false;
}

void BindingsMenu::syncPause(render::Controls& controls) {
  if (m_open && !m_pauseApplied) {
    m_pausedBefore = controls.paused;
    controls.paused = true;
    m_pauseApplied = true;
  } else if (!m_open && m_pauseApplied) {
    controls.paused = m_pausedBefore;
    m_pauseApplied = false;
  }
}

Status BindingsMenu::save() {
  Status st = input::saveOverrides(m_path, m_input.overrides());
  if (st) {
    m_status = "saved to " + m_path;
    m_dirty = false;
  } else {
    m_status = "not saved: " + st.error();
  }
  return st;
}

void BindingsMenu::rebind(int action, int slot) {
  m_captureAction = action;
  m_captureSlot = slot;
  m_waitingPositive = false;
  m_input.beginCapture();
}

void BindingsMenu::finishCapture() {
  auto got = m_input.takeCaptured();
  if (!got) return;
  const int a = m_captureAction;
  if (!got->first) {  // Escape
    m_captureAction = -1;
    m_waitingPositive = false;
    return;
  }
  const input::ActionDef& def = m_input.action(a);
  input::Source src = got->second;
  input::Binding b;
  // Modifiers: those of the binding being replaced if it is the same kind of
  // input, else of a default binding of that kind (a new stick keeps the
  // stick's dead zone), else the action's.
  b.modifiers = def.modifiers;
  const std::vector<input::Binding>& current = m_input.bindings(a);
  if (m_captureSlot >= 0 && m_captureSlot < int(current.size()) &&
      current[std::size_t(m_captureSlot)].source.device == src.device) {
    b.modifiers = current[std::size_t(m_captureSlot)].modifiers;
  } else {
    for (const input::Binding& d : def.bindings)
      if (d.source.device == src.device) {
        b.modifiers = d.modifiers;
        break;
      }
  }
  if (def.type == input::ActionType::Axis) {
    if (src.device == input::Device::PadAxis) src.half = 0;  // a stick drives the whole axis
    if (src.device == input::Device::Key && !m_waitingPositive) {
      // A key on an axis: it is the negative half of a key pair; ask for the other.
      m_pairNegative = src;
      m_waitingPositive = true;
      m_input.beginCapture();
      return;
    }
    if (m_waitingPositive) {
      if (src.device != input::Device::Key) {
        m_status = "a key pair needs a second key (Escape cancels)";
        m_input.beginCapture();
        return;
      }
      b.pair = true;
      b.source = m_pairNegative;
      b.positive = src;
      m_waitingPositive = false;
    } else {
      b.source = src;
    }
  } else {
    b.source = src;
  }
  std::vector<input::Binding> list = m_input.bindings(a);
  if (m_captureSlot >= 0 && m_captureSlot < int(list.size())) list[std::size_t(m_captureSlot)] = b;
  else list.push_back(b);
  m_input.setBindings(a, std::move(list));
  m_dirty = true;
  m_captureAction = -1;
}

void BindingsMenu::drawAction(int a) {
  const input::ActionDef& def = m_input.action(a);
  ImGui::PushID(a);
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextUnformatted((def.label.empty() ? def.name : def.label).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s (%s)", def.name.c_str(), def.type == input::ActionType::Axis ? "axis" : "button");
  ImGui::TableSetColumnIndex(1);
  std::vector<input::Binding> list = m_input.bindings(a);
  int remove = -1;
  for (std::size_t i = 0; i < list.size(); ++i) {
    ImGui::PushID(int(i));
    const bool capturingThis = m_captureAction == a && m_captureSlot == int(i);
    std::string label = capturingThis ? (m_waitingPositive ? "press the + key..." : "press a key...")
                                      : input::bindingLabel(list[i]);
    if (ImGui::SmallButton(label.c_str()) && m_captureAction < 0) rebind(a, int(i));
    const ImVec2 at = ImGui::GetItemRectMin(), size = ImGui::GetItemRectSize();
    m_layout.push_back({def.name, label, int(i), at.x, at.y, size.x, size.y});
    ImGui::SameLine(0, 2);
    if (ImGui::SmallButton("x")) remove = int(i);
    ImGui::SameLine();
    ImGui::PopID();
  }
  const bool addingHere = m_captureAction == a && m_captureSlot < 0;
  if (ImGui::SmallButton(addingHere ? (m_waitingPositive ? "press the + key..." : "press a key...") : "+") &&
      m_captureAction < 0)
    rebind(a, -1);
  ImGui::TableSetColumnIndex(2);
  const bool isDefault = list == def.bindings;
  if (isDefault) ImGui::BeginDisabled();
  if (ImGui::SmallButton("Reset")) {
    m_input.resetBindings(a);
    m_dirty = true;
  }
  if (isDefault) ImGui::EndDisabled();
  if (remove >= 0) {
    list.erase(list.begin() + remove);
    m_input.setBindings(a, std::move(list));
    m_dirty = true;
  }
  ImGui::PopID();
}

void BindingsMenu::draw() {
  if (!m_open) return;
  m_layout.clear();
  if (m_captureAction >= 0) finishCapture();
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(std::min(760.0f, display.x * 0.9f), std::min(560.0f, display.y * 0.85f)),
                           ImGuiCond_Appearing);
  bool open = true;
  if (ImGui::Begin("Bindings", &open, ImGuiWindowFlags_NoCollapse)) {
    ImGui::TextWrapped("Click a binding to change it and press the new key, mouse button or pad button "
                       "(Escape cancels; an axis takes a stick or two keys, - then +). x removes, + adds.");
    // Contexts in priority order: the one that wins a shared key comes first.
    std::vector<input::ContextDef> contexts = m_input.definitions().contexts;
    std::stable_sort(contexts.begin(), contexts.end(),
                     [](const auto& x, const auto& y) { return x.priority > y.priority; });
    for (const input::ContextDef& c : contexts) {
      std::string header = c.name + " (priority " + std::to_string(c.priority) +
                           (m_input.contextEnabled(c.name) ? ", on)" : ", off)");
      if (!ImGui::CollapsingHeader(header.c_str(), ImGuiTreeNodeFlags_DefaultOpen)) continue;
      if (ImGui::BeginTable(c.name.c_str(), 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        ImGui::TableSetupColumn("action", ImGuiTableColumnFlags_WidthFixed, 190.0f);
        ImGui::TableSetupColumn("bindings", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableSetupColumn("reset", ImGuiTableColumnFlags_WidthFixed, 50.0f);
        for (int a = 0; a < m_input.actionCount(); ++a)
          if (m_input.action(a).context == c.name) drawAction(a);
        ImGui::EndTable();
      }
    }
    ImGui::Separator();
    if (ImGui::Button("Save")) (void)save();
    ImGui::SameLine();
    if (ImGui::Button("Reset all to defaults")) {
      m_input.resetAllBindings();
      m_dirty = true;
    }
    ImGui::SameLine();
    ImGui::TextDisabled("%s", m_dirty ? "unsaved changes" : "");
    if (!m_status.empty()) ImGui::TextWrapped("%s", m_status.c_str());
  }
  ImGui::End();
  if (!open) toggle();
}

void applyFrameInput(input::InputSystem& input, BindingsMenu& menu, render::Controls& controls,
                     render::Renderer& renderer, PauseMenu* pauseMenu, FrameRequests* requests) {
  render::Camera& camera = renderer.camera();
  for (int a : input.takeFramePresses()) {
    const std::string& name = input.action(a).name;
    if (name == "pause") controls.paused = !controls.paused;
    else if (name == "screenshot") controls.screenshotRequested = true;
    else if (name == "menu") menu.toggle();
    else if (name == "camera") camera.mode = render::nextCameraMode(camera.mode, camera.vehicleModes);
    else if (name == "debug_panel") controls.debugPanelVisible = !controls.debugPanelVisible;
    else if (name == "pause_menu" && menu.isOpen()) menu.toggle();  // Escape closes the bindings menu only
    else if (name == "pause_menu" && pauseMenu) pauseMenu->toggle();
    else if (name == "ui_up" && pauseMenu) pauseMenu->moveSelection(-1);
    else if (name == "ui_down" && pauseMenu) pauseMenu->moveSelection(+1);
    else if (name == "ui_select" && pauseMenu) pauseMenu->activate();
    else if (name == "restart" && requests) requests->restart = true;
    else if (name == "console" && requests) requests->toggleConsole = true;
    else if (name == "hud" && requests) requests->toggleHud = true;
  }
  if (pauseMenu) {
    switch (pauseMenu->takeChoice()) {
      case PauseMenu::Choice::Restart:
        if (requests) requests->restart = true;
        break;
      case PauseMenu::Choice::Quit: controls.quitRequested = true; break;
      case PauseMenu::Choice::ChangeVehicle:
        if (requests) requests->changeVehicle = true;
        break;
      case PauseMenu::Choice::Settings:
        if (requests) requests->settings = true;
        break;
      case PauseMenu::Choice::MainMenu:
        if (requests) requests->mainMenu = true;
        break;
      case PauseMenu::Choice::BackToDesigner:
        if (requests) requests->backToDesigner = true;
        break;
      case PauseMenu::Choice::Resume:
      case PauseMenu::Choice::None: break;
    }
    pauseMenu->syncPause(controls);
  }
  menu.syncPause(controls);
  if (auto p = input.pointer()) {
    auto [origin, direction] = renderer.viewRay((*p)[0], (*p)[1]);
    input.setPointerRay(origin.cast<Real>(), direction.cast<Real>());
  }
}

}  // namespace tumble::app
