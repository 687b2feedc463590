#include "render/internal/hud.h"

#include <backends/imgui_impl_opengl3.h>
#include <backends/imgui_impl_sdl.h>
#include <imgui.h>
#include <imgui_internal.h>  // the frame's windows, for wantsMousePress

#include <cfloat>
#include <cstdio>
#include <iterator>
#include <optional>

#include "render/camera_rig.h"
#include "render/internal/time_scale.h"

namespace tumble::render {

namespace {

const ImVec4 kMessageColor(1.0f, 0.35f, 0.30f, 1.0f);
const ImVec4 kDimColor(0.70f, 0.70f, 0.70f, 1.0f);
constexpr float kMargin_px = 10.0f;
constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_AlwaysAutoResize |
                                           ImGuiWindowFlags_NoSavedSettings |
                                           ImGuiWindowFlags_NoFocusOnAppearing |
                                           ImGuiWindowFlags_NoNav;

void timingRow(const char* name, double ms) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextUnformatted(name);
  ImGui::TableSetColumnIndex(1);
  ImGui::Text("%6.2f ms", ms);
}

}  // namespace

Result<std::unique_ptr<Hud>> Hud::create(SDL_Window* window, SDL_GLContext context) {
  std::unique_ptr<Hud> hud(new Hud());
  hud->m_context = ImGui::CreateContext();
  ImGui::SetCurrentContext(hud->m_context);
  ImGuiIO& io = ImGui::GetIO();
  // No imgui.ini in whatever directory the game was started from.
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 4.0f;

  hud->m_sdlBackend = ImGui_ImplSDL2_InitForOpenGL(window, context);
  if (!hud->m_sdlBackend) return makeError("HUD: Dear ImGui SDL2 backend failed to initialise");
  // The backend loads GL itself (gl3w through libGL.so.1); it fails if that
  // library is missing even when epoxy found GL through EGL.
  hud->m_glBackend = ImGui_ImplOpenGL3_Init("#version 330 core");
  if (!hud->m_glBackend) {
    return makeError("HUD: Dear ImGui OpenGL3 backend failed to initialise (needs libGL.so.1, "
                     "Debian: libgl1)");
  }
  return hud;
}

Hud::~Hud() {
  if (!m_context) return;
  ImGui::SetCurrentContext(m_context);
  if (m_glBackend) ImGui_ImplOpenGL3_Shutdown();
  if (m_sdlBackend) ImGui_ImplSDL2_Shutdown();
  ImGui::DestroyContext(m_context);
}

void Hud::processEvent(const SDL_Event& event) {
  ImGui::SetCurrentContext(m_context);
  ImGui_ImplSDL2_ProcessEvent(&event);
  if (event.type == SDL_WINDOWEVENT && event.window.event == SDL_WINDOWEVENT_LEAVE) m_haveMotion = false;
  if (event.type == SDL_MOUSEMOTION) {
    m_haveMotion = true;
    m_motionX = float(event.motion.x);
    m_motionY = float(event.motion.y);
  }
  if (event.type == SDL_MOUSEBUTTONDOWN || event.type == SDL_MOUSEBUTTONUP) {
    const int index = event.button.button == SDL_BUTTON_LEFT    ? 0
                      : event.button.button == SDL_BUTTON_RIGHT  ? 1
                      : event.button.button == SDL_BUTTON_MIDDLE ? 2
                                                                 : -1;
    if (index >= 0) m_held[index] = event.type == SDL_MOUSEBUTTONDOWN;
    m_haveMotion = true;
    m_motionX = float(event.button.x);
    m_motionY = float(event.button.y);
  }
}

bool Hud::wantsKeyboard() const {
  ImGui::SetCurrentContext(m_context);
  return ImGui::GetIO().WantCaptureKeyboard;
}

bool Hud::wantsMouse() const {
  ImGui::SetCurrentContext(m_context);
  return ImGui::GetIO().WantCaptureMouse;
}

bool Hud::wantsMousePress(float x_px, float y_px) const {
  if (m_popupOpen) return true;
  for (const auto& r : m_mouseWindows)
    if (x_px >= r[0] && y_px >= r[1] && x_px < r[2] && y_px < r[3]) return true;
  return false;
}

void Hud::newFrame() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplSDL2_NewFrame();
  // The SDL backend (1.86) reads the pointer from SDL's mouse focus and
  // state, which the offscreen driver (play --frames) never sets: there the
  // last motion event is where the pointer is.
  ImGuiIO& io = ImGui::GetIO();
  for (int i = 0; i < 3; ++i) io.MouseDown[i] = io.MouseDown[i] || m_held[i];
  if (m_haveMotion) io.MousePos = ImVec2(m_motionX, m_motionY);
  ImGui::NewFrame();
}

void Hud::draw(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning) {
  ImGui::SetCurrentContext(m_context);
  // ImGui hides an auto-sized window on the frame it appears while it
  // measures the contents. A `run --screenshot` may render only one frame,
  // and a script error should be visible in the very frame it is reported,
  // so when a window appears lay the HUD out once without drawing it (and
  // without applying its button presses). Layout costs microseconds.
  const bool hasMessages = !stats.messages.empty();
  const bool hasTuning = tuning && controls.tuningPanelVisible;
  if (!m_primed || (hasMessages && !m_hadMessages) || (hasTuning && !m_hadTuning)) {
    Controls scratch = controls;
    std::optional<TuningPanel> panelScratch;
    if (tuning) panelScratch = *tuning;
    newFrame();
    build(stats, scratch, cameraMode, panelScratch ? &*panelScratch : nullptr);
    ImGui::EndFrame();
    m_primed = true;
  }
  m_hadMessages = hasMessages;
  m_hadTuning = hasTuning;
  newFrame();
  build(stats, controls, cameraMode, tuning);
  m_popupOpen = ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel);
  ImGui::Render();
  m_mouseWindows.clear();
  for (const ImGuiWindow* w : ImGui::GetCurrentContext()->Windows)
    if (w->Active && !w->Hidden && !(w->Flags & ImGuiWindowFlags_NoMouseInputs))
      m_mouseWindows.push_back({w->Pos.x, w->Pos.y, w->Pos.x + w->Size.x, w->Pos.y + w->Size.y});
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Hud::build(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;

  if (controls.debugPanelVisible) buildDebugPanel(stats, controls, cameraMode, tuning);
  if (tuning && controls.tuningPanelVisible) buildTuningPanel(*tuning, &controls.tuningPanelVisible);
  buildMessages(stats, display);
  for (const HudPanel& panel : m_panels) panel();
}

void Hud::buildDebugPanel(const HudStats& stats, Controls& controls, CameraMode cameraMode, TuningPanel* tuning) {
  ImGui::SetNextWindowPos(ImVec2(kMargin_px, kMargin_px), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.72f);
  if (ImGui::Begin("Tumble", nullptr, kOverlayFlags | ImGuiWindowFlags_NoMove)) {
    ImGui::Text("%s", stats.scenario.empty() ? "(no scenario)" : stats.scenario.c_str());
    ImGui::Separator();
    // A single picture (run --screenshot, offscreen play) has no frame rate.
    if (stats.fps > 0) ImGui::Text("%.0f FPS  (%.2f ms)", stats.fps, 1000.0 / stats.fps);
    else ImGui::TextColored(kDimColor, "single frame (no frame rate)");
    if (ImGui::BeginTable("timings", 2, ImGuiTableFlags_SizingFixedFit)) {
      timingRow("physics", stats.physics_ms);
      timingRow("script", stats.script_ms);
      timingRow("particles", stats.particles_ms);
      timingRow("render", stats.render_ms);
      ImGui::EndTable();
    }
    ImGui::Separator();
    ImGui::Text("sim time  %.2f s", stats.simTime_s);
    ImGui::Text("bodies    %d", stats.bodies);
    ImGui::Text("contacts  %d", stats.contacts);
    ImGui::Separator();

    if (ImGui::Button(controls.paused ? "Resume" : "Pause", ImVec2(64, 0))) {
      controls.paused = !controls.paused;
    }
    ImGui::SameLine();
    if (ImGui::Button("Step", ImVec2(64, 0))) requestSingleStep(controls);

    int level = timeScaleIndex(controls.timeScale);
    char label[16];
    std::snprintf(label, sizeof label, "x%g", static_cast<double>(kTimeScales[level]));
    ImGui::SetNextItemWidth(132);
    // The format string is the label itself: the slider shows "x0.25", not the index.
    if (ImGui::SliderInt("speed", &level, 0, static_cast<int>(std::size(kTimeScales)) - 1, label,
                         ImGuiSliderFlags_AlwaysClamp)) {
      controls.timeScale = kTimeScales[level];
    }
    ImGui::TextColored(kDimColor, "camera: %s (C)", cameraModeName(cameraMode));
    ImGui::TextColored(kDimColor, "P pause  N step  -/= speed  F12 shot  F1 keys");
    ImGui::TextColored(kDimColor, "F4 hides this panel");
    if (ImGui::Button(controls.collisionView ? "Models (F3)" : "Collision (F3)", ImVec2(132, 0)))
      controls.collisionView = !controls.collisionView;
    if (tuning) {
      if (ImGui::Button(controls.tuningPanelVisible ? "Hide tuning (F2)" : "Tune (F2)", ImVec2(132, 0)))
        controls.tuningPanelVisible = !controls.tuningPanelVisible;
    }
  }
  ImGui::End();
}

void Hud::buildMessages(const HudStats& stats, const ImVec2& display) {
  if (!stats.messages.empty()) {
    ImGui::SetNextWindowPos(ImVec2(kMargin_px, display.y - kMargin_px), ImGuiCond_Always,
                            ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowSizeConstraints(ImVec2(0, 0), ImVec2(display.x * 0.8f, display.y * 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("Messages", nullptr, kOverlayFlags | ImGuiWindowFlags_NoMove)) {
      ImGui::PushStyleColor(ImGuiCol_Text, kMessageColor);
      ImGui::PushTextWrapPos(display.x * 0.8f - 2.0f * kMargin_px);
      for (const std::string& message : stats.messages) ImGui::TextUnformatted(message.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopStyleColor();
    }
    ImGui::End();
  }
}

}  // namespace tumble::render
