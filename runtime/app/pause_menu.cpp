#include "app/pause_menu.h"

#include <imgui.h>

#include <algorithm>


namespace tumble::app {

namespace {

constexpr const char* kUiContext = "ui";
constexpr float kItemWidth_px = 280.0f, kItemHeight_px = 46.0f;
const ImVec4 kHighlight(0.95f, 0.62f, 0.12f, 1.0f);   // the keyboard / pad selection
const ImVec4 kItemColor(0.18f, 0.20f, 0.24f, 0.95f);
const ImVec4 kItemHover(0.30f, 0.34f, 0.40f, 1.0f);

}  // namespace

PauseMenu::PauseMenu() { setVehicleChoice(false); }

void PauseMenu::setDesignerReturn(bool offered) {
  m_designerReturn = offered;
  setVehicleChoice(m_vehicleOffered);
}

void PauseMenu::setVehicleChoice(bool offered) {
  m_vehicleOffered = offered;
  m_items = {{"Resume", Choice::Resume}, {"Restart", Choice::Restart}};
  if (m_designerReturn) m_items.push_back({"Back to designer", Choice::BackToDesigner});
  if (offered) m_items.push_back({"Change vehicle", Choice::ChangeVehicle});
  m_items.push_back({"Settings", Choice::Settings});
  m_items.push_back({"Main menu", Choice::MainMenu});
  m_items.push_back({"Quit to desktop", Choice::Quit});
  m_selected = std::min(m_selected, int(m_items.size()) - 1);
}

void PauseMenu::setInput(input::InputSystem* input) {
  m_input = input;
  syncUiContext();  // a new input system starts with the context off
}

// The `ui` context is on exactly while the menu is open. Mods that do not
// declare it (a scene with its own bindings) leave the keyboard navigation
// out; the mouse still works.
void PauseMenu::syncUiContext() {
  if (!m_input) return;
  const auto names = m_input->contextNames();
  if (std::find(names.begin(), names.end(), kUiContext) != names.end())
    (void)m_input->setContextEnabled(kUiContext, m_open);
}

void PauseMenu::open() {
  m_open = true;
  m_selected = 0;
  m_choice = Choice::None;
  syncUiContext();
}

void PauseMenu::close() {
  m_open = false;
  syncUiContext();
}

void PauseMenu::syncPause(render::Controls& controls) {
  if (m_open && !m_pauseApplied) {
    m_pausedBefore = controls.paused;
    controls.paused = true;
    m_pauseApplied = true;
  } else if (!m_open && m_pauseApplied) {
    controls.paused = m_pausedBefore;
    m_pauseApplied = false;
  }
}

void PauseMenu::moveSelection(int delta) {
  if (!m_open || m_items.empty()) return;
  const int n = int(m_items.size());
  m_selected = ((m_selected + delta) % n + n) % n;
}

void PauseMenu::activate() {
  if (m_open && m_selected >= 0 && m_selected < int(m_items.size())) choose(m_items[std::size_t(m_selected)].choice);
}

void PauseMenu::choose(Choice c) {
  m_choice = c;
  close();
}

PauseMenu::Choice PauseMenu::takeChoice() {
  const Choice c = m_choice;
  m_choice = Choice::None;
  return c;
}

void PauseMenu::draw() {
  m_layout.clear();
  if (!m_open) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  // Dim the game behind the menu.
  ImGui::GetBackgroundDrawList()->AddRectFilled(ImVec2(0, 0), display, IM_COL32(0, 0, 0, 110));
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.88f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoCollapse;
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(24, 20));
  ImGui::PushStyleVar(ImGuiStyleVar_ItemSpacing, ImVec2(8, 10));
  ImGui::PushStyleVar(ImGuiStyleVar_FrameRounding, 6.0f);
  if (ImGui::Begin("Paused", nullptr, flags)) {
    ImGui::SetWindowFontScale(1.6f);
    const char* title = "PAUSED";
    ImGui::SetCursorPosX((ImGui::GetWindowSize().x - ImGui::CalcTextSize(title).x) * 0.5f);
    ImGui::TextUnformatted(title);
    ImGui::Separator();
    ImGui::SetWindowFontScale(1.3f);
    for (int i = 0; i < int(m_items.size()); ++i) {
      const bool highlighted = i == m_selected;
      ImGui::PushStyleColor(ImGuiCol_Button, highlighted ? kHighlight : kItemColor);
      ImGui::PushStyleColor(ImGuiCol_ButtonHovered, highlighted ? kHighlight : kItemHover);
      ImGui::PushStyleColor(ImGuiCol_Text, highlighted ? ImVec4(0.08f, 0.08f, 0.08f, 1.0f) : ImVec4(1, 1, 1, 1));
      const Item& item = m_items[std::size_t(i)];
      const ImVec2 at = ImGui::GetCursorScreenPos();
      if (ImGui::Button(item.label.c_str(), ImVec2(kItemWidth_px, kItemHeight_px))) {
        m_selected = i;
        choose(item.choice);
      }
      // The pointer picks what it moves over; resting on an item does not
      // undo the keyboard's choice.
      const ImVec2 moved = ImGui::GetIO().MouseDelta;
      if (ImGui::IsItemHovered() && (moved.x != 0 || moved.y != 0)) m_selected = i;
      ImGui::PopStyleColor(3);
      m_layout.push_back({item.label, at.x, at.y, kItemWidth_px, kItemHeight_px});
    }
    ImGui::SetWindowFontScale(1.0f);
    ImGui::TextDisabled("Escape: resume   Up/Down, Enter: choose");
  }
  ImGui::End();
  ImGui::PopStyleVar(3);
}

}  // namespace tumble::app
