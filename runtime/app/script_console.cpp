#include "app/script_console.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

namespace tumble::app {

namespace {
const ImVec4 kErrorColor(1.0f, 0.38f, 0.32f, 1.0f);
const ImVec4 kFileColor(0.55f, 0.80f, 1.0f, 1.0f);
}  // namespace

void ScriptConsole::sync(const script::ScenarioHost& host) {
  const auto& errors = host.errors();
  for (; m_seen < errors.size(); ++m_seen) {
    const script::ScriptError& e = errors[m_seen];
    m_entries.push_back({e.mod, e.file, e.message, e.traceback, e.line});
  }
  if (m_entries.size() > kMaxEntries)
    m_entries.erase(m_entries.begin(), m_entries.end() - std::ptrdiff_t(kMaxEntries));
}

void ScriptConsole::draw() {
  m_clearButton = Rect{};
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float scale = std::clamp(std::min(display.x / 1280.0f, display.y / 720.0f), 0.6f, 2.0f);
  if (!m_open) {
    if (m_entries.empty()) return;
    // The badge: a red pill at the top centre.
    char text[64];
    std::snprintf(text, sizeof text, "%zu script error%s  ( ` )", m_entries.size(), m_entries.size() == 1 ? "" : "s");
    ImFont* font = ImGui::GetFont();
    const float size = ImGui::GetFontSize() * 1.2f * scale;
    const ImVec2 t = font->CalcTextSizeA(size, 1e9f, 0, text);
    const ImVec2 pad(10 * scale, 4 * scale);
    const ImVec2 a(display.x * 0.5f - t.x * 0.5f - pad.x, 6 * scale);
    const ImVec2 b(a.x + t.x + 2 * pad.x, a.y + t.y + 2 * pad.y);
    ImDrawList* dl = ImGui::GetForegroundDrawList();
    dl->AddRectFilled(a, b, IM_COL32(170, 30, 30, 220), 8 * scale);
    dl->AddText(font, size, ImVec2(a.x + pad.x, a.y + pad.y), IM_COL32(255, 255, 255, 255), text);
    return;
  }
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.05f, display.y * 0.05f), ImGuiCond_Appearing);
  ImGui::SetNextWindowSize(ImVec2(display.x * 0.9f, display.y * 0.45f), ImGuiCond_Appearing);
  ImGui::SetNextWindowBgAlpha(0.9f);
  bool open = true;
  if (ImGui::Begin("Script errors", &open, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
    if (ImGui::Button("Clear")) clear();
    const ImVec2 at = ImGui::GetItemRectMin(), size = ImGui::GetItemRectSize();
    m_clearButton = Rect{at.x, at.y, size.x, size.y};
    ImGui::SameLine();
    ImGui::TextDisabled("%zu error%s, newest last   ` closes", m_entries.size(), m_entries.size() == 1 ? "" : "s");
    ImGui::Separator();
    ImGui::BeginChild("entries");
    for (std::size_t i = 0; i < m_entries.size(); ++i) {
      const Entry& e = m_entries[i];
      ImGui::PushID(int(i));
      std::string where = e.mod + ": " + e.file;
      if (e.line > 0) where.append(":").append(std::to_string(e.line));
      ImGui::TextColored(kFileColor, "%s", where.c_str());
      ImGui::SameLine();
      ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
      ImGui::TextWrapped("%s", e.message.c_str());
      ImGui::PopStyleColor();
      if (!e.traceback.empty() && ImGui::TreeNode("traceback")) {
        ImGui::TextDisabled("%s", e.traceback.c_str());
        ImGui::TreePop();
      }
      ImGui::PopID();
    }
    if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);  // follow the newest
    ImGui::EndChild();
  }
  ImGui::End();
  if (!open) m_open = false;
}

}  // namespace tumble::app
