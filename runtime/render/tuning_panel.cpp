// The tuning panel (F2): a Dear ImGui window listing the scenario's
// tunables with a widget each, a reset button per value, and "Save" / "Reset
// all". It edits the plain TuningPanel the app hands over (renderer.h); the
// app applies the edits to the script's tunables after the frame, so a
// change is live at the next fixed step.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include "render/internal/hud.h"
#include "render/renderer.h"

namespace tumble::render {

TuningWidget tuningWidgetFor(const TuningItem& item) {
  switch (item.kind) {
    case TuningItem::Kind::Bool: return TuningWidget::Checkbox;
    case TuningItem::Kind::Choice: return TuningWidget::Combo;
    case TuningItem::Kind::Number: break;
  }
  return std::isfinite(item.min) && std::isfinite(item.max) ? TuningWidget::Slider : TuningWidget::Drag;
}

std::string tuningValueText(const TuningItem& item) {
  switch (item.kind) {
    case TuningItem::Kind::Bool: return item.value != 0 ? "on" : "off";
    case TuningItem::Kind::Choice: {
      auto i = static_cast<std::size_t>(item.value);
      return i < item.choices.size() ? item.choices[i] : std::string("?");
    }
    case TuningItem::Kind::Number: break;
  }
  char text[64];
  std::snprintf(text, sizeof text, "%g", item.value);
  return item.unit.empty() ? std::string(text) : std::string(text) + " " + item.unit;
}

double tuningSnap(const TuningItem& item, double value) {
  if (item.step > 0) {
    const double origin = std::isfinite(item.min) ? item.min : 0.0;
    value = origin + std::round((value - origin) / item.step) * item.step;
  }
  if (std::isfinite(item.min)) value = std::max(value, item.min);
  if (std::isfinite(item.max)) value = std::min(value, item.max);
  return value;
}

namespace {

const ImVec4 kChangedColor(1.0f, 0.80f, 0.35f, 1.0f);  // a value the user changed
const ImVec4 kDim(0.70f, 0.70f, 0.70f, 1.0f);

void numberWidget(TuningItem& item) {
  double v = item.value;
  char format[48];
  std::snprintf(format, sizeof format, "%%.4g%s%s", item.unit.empty() ? "" : " ", item.unit.c_str());
  bool changed = false;
  if (tuningWidgetFor(item) == TuningWidget::Slider) {
    changed = ImGui::SliderScalar("##v", ImGuiDataType_Double, &v, &item.min, &item.max, format);
  } else {
    // Unbounded: a drag whose speed follows the value's size.
    const float speed = float(item.step > 0 ? item.step : std::max(1e-3, std::abs(v) * 0.01));
    changed = ImGui::DragScalar("##v", ImGuiDataType_Double, &v, speed, nullptr, nullptr, format);
  }
  if (changed) {
    v = tuningSnap(item, v);
    if (v != item.value) {
      item.value = v;
      item.edited = true;
    }
  }
}

void itemRow(TuningItem& item) {
  ImGui::PushID(item.name.c_str());
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  if (item.userSet) ImGui::TextColored(kChangedColor, "%s", item.name.c_str());
  else ImGui::TextUnformatted(item.name.c_str());
  if (!item.description.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", item.description.c_str());
  ImGui::TableSetColumnIndex(1);
  ImGui::SetNextItemWidth(-FLT_MIN);
  switch (tuningWidgetFor(item)) {
    case TuningWidget::Slider:
    case TuningWidget::Drag: numberWidget(item); break;
    case TuningWidget::Checkbox: {
      bool on = item.value != 0;
      if (ImGui::Checkbox("##v", &on)) {
        item.value = on ? 1 : 0;
        item.edited = true;
      }
      break;
    }
    case TuningWidget::Combo: {
      int index = int(item.value);
      const char* preview = index >= 0 && index < int(item.choices.size()) ? item.choices[std::size_t(index)].c_str() : "";
      if (ImGui::BeginCombo("##v", preview)) {
        for (int i = 0; i < int(item.choices.size()); ++i) {
          if (ImGui::Selectable(item.choices[std::size_t(i)].c_str(), i == index) && i != index) {
            item.value = i;
            item.edited = true;
          }
        }
        ImGui::EndCombo();
      }
      break;
    }
  }
  ImGui::TableSetColumnIndex(2);
  if (!item.userSet) ImGui::BeginDisabled();
  if (ImGui::SmallButton("reset")) item.resetRequested = true;
  if (!item.userSet) ImGui::EndDisabled();
  ImGui::PopID();
}

}  // namespace

void buildTuningPanel(TuningPanel& panel, bool* open) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x - 10.0f, 10.0f), ImGuiCond_FirstUseEver, ImVec2(1.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (ImGui::Begin("Tuning", open, ImGuiWindowFlags_NoSavedSettings)) {
    if (!panel.title.empty()) ImGui::TextUnformatted(panel.title.c_str());
    if (panel.items.empty()) {
      ImGui::TextColored(kDim, "This scenario declares no tunables.");
      ImGui::TextColored(kDim, "Add one: tune.number(\"speed\", 2, {min = 0, max = 10})");
    } else if (ImGui::BeginTable("tunables", 3, ImGuiTableFlags_SizingStretchProp)) {
      ImGui::TableSetupColumn("name", ImGuiTableColumnFlags_WidthFixed);
      ImGui::TableSetupColumn("value", ImGuiTableColumnFlags_WidthStretch);
      ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
      for (TuningItem& item : panel.items) itemRow(item);
      ImGui::EndTable();
    }
    ImGui::Separator();
    if (ImGui::Button("Save")) panel.saveRequested = true;
    if (ImGui::IsItemHovered() && !panel.overridesPath.empty())
      ImGui::SetTooltip("writes %s; loaded the next time this mod plays", panel.overridesPath.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Reset all")) panel.resetAllRequested = true;
    if (!panel.status.empty()) ImGui::TextColored(kDim, "%s", panel.status.c_str());
  }
  ImGui::End();
}

}  // namespace tumble::render
