#include "app/driving_hud.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/log.h"
#include "vehicle/vehicle_system.h"
#ifdef TUMBLE_HAVE_TERRAIN
#include "app/terrain_scene.h"
#endif

namespace tumble::app {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr double kDialMax_kmh = 200;  ///< the speedometer's scale end; faster pins the needle, the digits go on
const ImU32 kPanel = IM_COL32(8, 10, 14, 150);
const ImU32 kWhite = IM_COL32(245, 245, 245, 255);
const ImU32 kDim = IM_COL32(170, 175, 185, 255);
const ImU32 kAccent = IM_COL32(255, 170, 40, 255);
const ImU32 kRed = IM_COL32(230, 50, 40, 255);

ImU32 withAlpha(ImU32 c, float a) {
  const ImU32 alpha = ImU32(std::clamp(a, 0.0f, 1.0f) * float((c >> 24) & 0xFF) + 0.5f);
  return (c & 0x00FFFFFFu) | alpha << 24;
}

ImU32 kindColor(script::MessageKind k) {
  switch (k) {
    case script::MessageKind::Warning: return IM_COL32(255, 210, 60, 255);
    case script::MessageKind::Error: return IM_COL32(255, 90, 80, 255);
    case script::MessageKind::Info: break;
  }
  return kWhite;
}

// Text of `size` px with its top-left at p; align 0 left, 0.5 centre, 1 right of p.x.
void text(ImDrawList* dl, float size, ImVec2 p, ImU32 col, const std::string& s, float align = 0) {
  ImFont* font = ImGui::GetFont();
  if (align != 0) p.x -= font->CalcTextSizeA(size, 1e9f, 0, s.c_str()).x * align;
  dl->AddText(font, size, p, col, s.c_str());
}

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// The first vehicle the camera follows, else the first vehicle.
std::optional<vehicle::VehicleId> drivenVehicle(Scene& scene) {
  const vehicle::VehicleSystem* vs = scene.vehiclesIfAny();
  if (!vs || vs->count() == 0) return std::nullopt;
  const auto& target = scene.host().presentation().camera.target;
  std::optional<vehicle::VehicleId> first, followed;
  vs->forEach([&](vehicle::VehicleId id) {
    if (!first) first = id;
    if (!followed && target && vs->chassis(id) == *target) followed = id;
  });
  return followed ? followed : first;
}

}  // namespace

std::string gearText(int gear) {
  if (gear < 0) return "R";
  if (gear == 0) return "N";
  return std::to_string(gear);
}

std::string lapTimeText(std::optional<double> seconds) {
  if (!seconds) return "-";
  const double t = std::max(0.0, *seconds);
  const long long cs = std::llround(t * 100);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%lld:%02lld.%02lld", cs / 6000, (cs / 100) % 60, cs % 100);
  return buf;
}

void GameHud::update(Scene& scene, double time_s) {
  m_drawn = false;
  script::ScenarioHost& host = scene.host();
  m_messages.update(host, time_s);
  m_console.sync(host);
  HudView v;
  v.visible = m_visible;
  v.messages = m_messages.visible(host, time_s);
  v.lap = host.presentation().lap;
  v.gates_m = host.presentation().gates_m;
  if (auto id = drivenVehicle(scene)) {
    const vehicle::VehicleSystem& vs = *scene.vehiclesIfAny();
    const vehicle::VehicleTelemetry& t = vs.telemetry(*id);
    const vehicle::VehicleDef& def = vs.def(*id);
    const physics::Body& body = scene.world().body(vs.chassis(*id));
    v.vehicle = true;
    v.vehicleName = def.name;
    v.speed_kmh = double(t.speed_mps) * 3.6;
    v.rpm = double(t.rpm);
    v.gear = t.gear;
    v.redline_rpm = double(def.engine.maxRpm);
    v.dialMax_rpm = std::ceil(v.redline_rpm * 1.15 / 1000.0) * 1000.0;
    v.speedText = format("%.0f", std::fabs(v.speed_kmh));
    v.rpmText = format("%.0f", std::max(0.0, v.rpm));
    v.gearText = gearText(t.gear);
    v.carX_m = float(body.position_m.x());
    v.carZ_m = float(body.position_m.z());
    const Vec3 f = body.orientation * Vec3::UnitZ();
    const float len = std::hypot(float(f.x()), float(f.z()));
    if (len > 1e-4f) v.forwardX = float(f.x()) / len, v.forwardZ = float(f.z()) / len;
  }
  if (v.lap.shown) {
    v.lapTimeText = lapTimeText(v.lap.time_s);
    v.lastText = lapTimeText(v.lap.last_s);
    v.bestText = lapTimeText(v.lap.best_s);
    if (v.lap.gates > 0) v.gateText = std::to_string(v.lap.gate) + " / " + std::to_string(v.lap.gates);
    if (v.lap.laps > 0) v.lapCountText = std::to_string(v.lap.lap) + " / " + std::to_string(v.lap.laps);
  }
  const render::TerrainSurface* surface = nullptr;
#ifdef TUMBLE_HAVE_TERRAIN
  if (const TerrainScene* ts = scene.terrainScene()) surface = &ts->surface();
#endif
  if (v.vehicle) m_minimap.update(surface);  // built once per terrain, on the first frame with a car
  else if (!surface) m_minimap.update(nullptr);
  if (m_renderer && m_minimapTextureBuild != m_minimap.builds()) {
    // Re-upload after a rebuild: software OpenGL pays per triangle, and a
    // rectangle per cell cost more than the rest of the HUD together.
    m_renderer->freeUiImage(m_minimapTexture);
    m_minimapTextureBuild = m_minimap.builds();
    if (!m_minimap.empty()) {
      auto texture = m_renderer->makeUiImage(m_minimap.rgba(), MinimapImage::kCells, MinimapImage::kCells);
      if (texture) m_minimapTexture = *texture;
      else log::warn("minimap: drawn cell by cell: " + texture.error());
    }
  }
  if (v.vehicle) v.minimap = !m_minimap.empty() && surface ? "terrain" : (!v.gates_m.empty() ? "plan" : "");
  m_view = std::move(v);
}

GameHud::~GameHud() {
  if (m_renderer) m_renderer->freeUiImage(m_minimapTexture);
}

void GameHud::draw() {
  m_drawn = m_view.visible;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float s = std::clamp(std::min(display.x / 1280.0f, display.y / 720.0f), 0.4f, 3.0f);
  if (m_view.visible) {
    if (m_view.vehicle) {
      drawSpeedometer(s);
      if (m_view.lap.shown) drawLap(s);
      if (!m_view.minimap.empty()) drawMinimap(s);
    }
    drawMessages(s);
  }
  m_console.draw();
}

void GameHud::drawSpeedometer(float s) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float base = ImGui::GetFontSize();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const float w = 330 * s, h = 236 * s, m = 16 * s;
  const ImVec2 a(display.x - m - w, display.y - m - h), b(display.x - m, display.y - m);
  dl->AddRectFilled(a, b, kPanel, 14 * s);
  // Dial: 270 degrees from bottom left, clockwise (screen y is down).
  const ImVec2 c(a.x + 112 * s, a.y + 108 * s);
  const float r = 90 * s, a0 = 0.75f * kPi, sweep = 1.5f * kPi;
  dl->PathArcTo(c, r, a0, a0 + sweep, 48);
  dl->PathStroke(IM_COL32(90, 95, 105, 230), 0, 4 * s);
  const float frac = float(std::clamp(std::fabs(m_view.speed_kmh) / kDialMax_kmh, 0.0, 1.0));
  if (frac > 0.002f) {
    dl->PathArcTo(c, r, a0, a0 + sweep * frac, 48);
    dl->PathStroke(kAccent, 0, 6 * s);
  }
  for (int k = 0; k <= int(kDialMax_kmh); k += 20) {
    const float ang = a0 + sweep * float(k / kDialMax_kmh);
    const ImVec2 dir(std::cos(ang), std::sin(ang));
    const bool major = k % 40 == 0;
    const float inner = r - (major ? 14 : 8) * s;
    dl->AddLine(ImVec2(c.x + dir.x * inner, c.y + dir.y * inner), ImVec2(c.x + dir.x * r, c.y + dir.y * r), kWhite,
                (major ? 2.5f : 1.5f) * s);
    if (major)
      text(dl, base * 1.0f * s, ImVec2(c.x + dir.x * (r - 30 * s), c.y + dir.y * (r - 30 * s) - base * 0.5f * s), kDim,
           std::to_string(k), 0.5f);
  }
  const float needle = a0 + sweep * frac;
  dl->AddLine(c, ImVec2(c.x + std::cos(needle) * (r - 6 * s), c.y + std::sin(needle) * (r - 6 * s)), kRed, 3.5f * s);
  dl->AddCircleFilled(c, 6 * s, kRed);
  text(dl, base * 3.4f * s, ImVec2(c.x, c.y + 18 * s), kWhite, m_view.speedText, 0.5f);
  text(dl, base * 1.2f * s, ImVec2(c.x, c.y + 18 * s + base * 3.4f * s), kDim, "km/h", 0.5f);
  // Gear, right column.
  const float gx = a.x + 272 * s;
  text(dl, base * 1.1f * s, ImVec2(gx, a.y + 18 * s), kDim, "GEAR", 0.5f);
  text(dl, base * 4.6f * s, ImVec2(gx, a.y + 36 * s), m_view.gear < 0 ? kAccent : kWhite, m_view.gearText, 0.5f);
  text(dl, base * 1.1f * s, ImVec2(gx, a.y + 118 * s), kDim, "RPM", 0.5f);
  const bool overRed = m_view.rpm >= m_view.redline_rpm;
  text(dl, base * 1.9f * s, ImVec2(gx, a.y + 134 * s), overRed ? kRed : kWhite, m_view.rpmText, 0.5f);
  // Rev counter: a bar along the bottom, red from the rev limiter on.
  const ImVec2 ra(a.x + 18 * s, b.y - 30 * s), rb(b.x - 18 * s, b.y - 16 * s);
  const float span = rb.x - ra.x;
  const float redX = ra.x + span * float(std::clamp(m_view.redline_rpm / m_view.dialMax_rpm, 0.0, 1.0));
  dl->AddRectFilled(ra, rb, IM_COL32(40, 44, 52, 230), 3 * s);
  dl->AddRectFilled(ImVec2(redX, ra.y), rb, IM_COL32(120, 20, 20, 230), 3 * s);
  const float fill = ra.x + span * float(std::clamp(m_view.rpm / m_view.dialMax_rpm, 0.0, 1.0));
  if (fill > ra.x) dl->AddRectFilled(ra, ImVec2(fill, rb.y), overRed ? kRed : kAccent, 3 * s);
  for (double k = 1000; k < m_view.dialMax_rpm; k += 1000) {
    const float x = ra.x + span * float(k / m_view.dialMax_rpm);
    dl->AddLine(ImVec2(x, ra.y - 4 * s), ImVec2(x, ra.y), kDim, 1.5f * s);
  }
}

void GameHud::drawLap(float s) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float base = ImGui::GetFontSize();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const HudView& v = m_view;
  const float w = 270 * s, m = 16 * s, line = base * 1.4f * s;
  float h = 18 * s + base * 1.2f * s + base * 3.0f * s + 2 * line + 12 * s;
  if (!v.gateText.empty()) h += line;
  const ImVec2 a(display.x - m - w, m), b(display.x - m, m + h);
  dl->AddRectFilled(a, b, kPanel, 14 * s);
  float y = a.y + 10 * s;
  const float x = a.x + 18 * s, xr = b.x - 18 * s;
  text(dl, base * 1.2f * s, ImVec2(x, y), kDim, v.lap.finished ? "FINISHED" : "LAP TIME");
  if (!v.lapCountText.empty()) text(dl, base * 1.2f * s, ImVec2(xr, y), kWhite, "LAP " + v.lapCountText, 1);
  y += base * 1.2f * s + 2 * s;
  text(dl, base * 3.0f * s, ImVec2(x, y), v.lap.finished ? kAccent : kWhite, v.lapTimeText);
  y += base * 3.0f * s + 6 * s;
  auto row = [&](const char* label, const std::string& value) {
    text(dl, base * 1.3f * s, ImVec2(x, y), kDim, label);
    text(dl, base * 1.3f * s, ImVec2(xr, y), kWhite, value, 1);
    y += line;
  };
  row("LAST", v.lastText);
  row("BEST", v.bestText);
  if (!v.gateText.empty()) row("GATE", v.gateText);
}

void GameHud::drawMinimap(float s) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float base = ImGui::GetFontSize();
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const HudView& v = m_view;
  const float size = 210 * s, m = 16 * s, pad = 8 * s;
  const ImVec2 a(m, display.y - m - size), b(m + size, display.y - m);
  dl->AddRectFilled(a, b, kPanel, 12 * s);
  const ImVec2 ia(a.x + pad, a.y + pad), ib(b.x - pad, b.y - pad);
  // World extent shown: the terrain, or the gates and the car with a margin.
  float x0, z0, x1, z1;
  if (v.minimap == "terrain") {
    x0 = m_minimap.minX_m, z0 = m_minimap.minZ_m, x1 = m_minimap.maxX_m, z1 = m_minimap.maxZ_m;
  } else {
    x0 = x1 = v.carX_m, z0 = z1 = v.carZ_m;
    for (const Vec3& g : v.gates_m) {
      x0 = std::min(x0, float(g.x())), x1 = std::max(x1, float(g.x()));
      z0 = std::min(z0, float(g.z())), z1 = std::max(z1, float(g.z()));
    }
    const float margin = 0.12f * std::max({x1 - x0, z1 - z0, 20.0f});
    x0 -= margin, x1 += margin, z0 -= margin, z1 += margin;
  }
  // Same scale on both axes, centred.
  const float side = ib.x - ia.x;
  const float k = side / std::max(x1 - x0, z1 - z0);
  const ImVec2 o(ia.x + (side - (x1 - x0) * k) * 0.5f, ia.y + (side - (z1 - z0) * k) * 0.5f);
  auto toScreen = [&](float x, float z) { return ImVec2(o.x + (x - x0) * k, o.y + (z - z0) * k); };
  dl->PushClipRect(ia, ib, true);
  if (v.minimap == "terrain" && m_minimapTexture.texture != 0) {
    dl->AddImage(ImTextureID(m_minimapTexture.texture), o, ImVec2(o.x + (x1 - x0) * k, o.y + (z1 - z0) * k));
  } else if (v.minimap == "terrain") {
    const int n = MinimapImage::kCells;
    const float cw = (x1 - x0) * k / float(n), ch = (z1 - z0) * k / float(n);
    for (int j = 0; j < n; ++j) {
      // Runs of one colour along the row: one rectangle each.
      for (int i = 0; i < n;) {
        const ImU32 col = m_minimap.color(i, j);
        int e = i + 1;
        while (e < n && m_minimap.color(e, j) == col) ++e;
        dl->AddRectFilled(ImVec2(o.x + float(i) * cw, o.y + float(j) * ch),
                          ImVec2(o.x + float(e) * cw + 0.5f, o.y + float(j + 1) * ch + 0.5f), col);
        i = e;
      }
    }
  } else {
    dl->AddRectFilled(ia, ib, IM_COL32(40, 44, 50, 200));
    for (std::size_t i = 0; i + 1 < v.gates_m.size(); ++i)  // the course, gate to gate
      dl->AddLine(toScreen(float(v.gates_m[i].x()), float(v.gates_m[i].z())),
                  toScreen(float(v.gates_m[i + 1].x()), float(v.gates_m[i + 1].z())), IM_COL32(120, 125, 135, 200),
                  2 * s);
  }
  for (std::size_t i = 0; i < v.gates_m.size(); ++i) {
    const int number = int(i) + 1;
    const bool next = number == v.lap.gate && !v.lap.finished;
    const bool passed = v.lap.shown && (v.lap.finished || number < v.lap.gate);
    const ImVec2 p = toScreen(float(v.gates_m[i].x()), float(v.gates_m[i].z()));
    const float rad = (next ? 9 : 6) * s;
    dl->AddCircleFilled(p, rad, next ? kAccent : passed ? IM_COL32(110, 110, 110, 230) : kWhite);
    dl->AddCircle(p, rad, IM_COL32(0, 0, 0, 200), 0, 1.5f * s);
    text(dl, base * 0.9f * s, ImVec2(p.x, p.y - base * 0.45f * s), IM_COL32(0, 0, 0, 255), std::to_string(number), 0.5f);
  }
  // The car: an arrow pointing where it heads.
  const ImVec2 c = toScreen(v.carX_m, v.carZ_m);
  const ImVec2 f(v.forwardX, v.forwardZ), r(-v.forwardZ, v.forwardX);
  const float len = 11 * s, half = 6 * s;
  const ImVec2 tip(c.x + f.x * len, c.y + f.y * len);
  const ImVec2 l(c.x - f.x * len * 0.6f + r.x * half, c.y - f.y * len * 0.6f + r.y * half);
  const ImVec2 rr(c.x - f.x * len * 0.6f - r.x * half, c.y - f.y * len * 0.6f - r.y * half);
  dl->AddTriangleFilled(tip, l, rr, kRed);
  dl->AddTriangle(tip, l, rr, kWhite, 1.5f * s);
  dl->PopClipRect();
}

void GameHud::drawMessages(float s) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float size = ImGui::GetFontSize() * 1.45f * s;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  ImFont* font = ImGui::GetFont();
  float y = 44 * s;
  const float wrap = display.x * 0.5f;
  int shown = 0;
  for (const HudMessage& msg : m_view.messages) {
    if (++shown > 10) break;
    const ImVec2 t = font->CalcTextSizeA(size, 1e9f, wrap, msg.text.c_str());
    const ImVec2 pad(10 * s, 4 * s);
    const ImVec2 a(display.x * 0.5f - t.x * 0.5f - pad.x, y), b(display.x * 0.5f + t.x * 0.5f + pad.x, y + t.y + 2 * pad.y);
    dl->AddRectFilled(a, b, withAlpha(IM_COL32(0, 0, 0, 140), msg.alpha), 6 * s);
    dl->AddText(font, size, ImVec2(a.x + pad.x, a.y + pad.y), withAlpha(kindColor(msg.kind), msg.alpha), msg.text.c_str(),
                nullptr, wrap);
    y = b.y + 4 * s;
  }
}

nlohmann::json GameHud::report() const {
  const HudView& v = m_view;
  nlohmann::json messages = nlohmann::json::array();
  for (const HudMessage& m : v.messages)
    messages.push_back({{"text", m.text}, {"kind", script::messageKindName(m.kind)}, {"alpha", m.alpha}});
  nlohmann::json entries = nlohmann::json::array();
  for (const ScriptConsole::Entry& e : m_console.entries())
    entries.push_back({{"mod", e.mod}, {"file", e.file}, {"line", e.line}, {"message", e.message},
                       {"where", e.file + ":" + std::to_string(e.line)}});
  const ScriptConsole::Rect& cb = m_console.clearButton();
  nlohmann::json out = {
      {"visible", v.visible},
      {"drawn", m_drawn},
      {"vehicle", v.vehicle},
      {"messages", messages},
      {"console", {{"open", m_console.isOpen()},
                   {"badge", !m_console.isOpen() && !entries.empty() ? int(entries.size()) : 0},
                   {"entries", entries},
                   {"clear_button", {{"x_px", cb.x_px}, {"y_px", cb.y_px}, {"w_px", cb.w_px}, {"h_px", cb.h_px}}}}},
      {"minimap", {{"shown", v.visible && v.vehicle && !v.minimap.empty()},
                   {"source", v.minimap},
                   {"builds", m_minimap.builds()},
                   {"gates", v.gates_m.size()}}},
  };
  if (v.vehicle) {
    out["vehicle_name"] = v.vehicleName;
    out["speed_kmh"] = v.speed_kmh;
    out["speed_text"] = v.speedText;
    out["rpm"] = v.rpm;
    out["rpm_text"] = v.rpmText;
    out["redline_rpm"] = v.redline_rpm;
    out["gear"] = v.gearText;
  }
  if (v.lap.shown)
    out["lap"] = {{"time_text", v.lapTimeText}, {"last_text", v.lastText}, {"best_text", v.bestText},
                  {"gate_text", v.gateText},   {"lap_text", v.lapCountText}, {"gate", v.lap.gate},
                  {"gates", v.lap.gates},      {"finished", v.lap.finished}};
  return out;
}

}  // namespace tumble::app
