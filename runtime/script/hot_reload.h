#pragma once
// HotReload: while playing, a saved file of the running mod takes effect.
// It watches the mod's folder (core/file_watch, polled at 4 Hz) and sends
// each saved .lua file to whoever owns that kind of file:
//   scenarios/<running>.lua, other .lua (require'd modules)  -> ScenarioHost::reload
//   emitters/*.lua, bindings.lua, vehicles/*.lua             -> hooks registered with addHook
//   mod.lua                                                  -> a note: restart to apply
// A hook returns a Status; an error is recorded on the host (HUD, report)
// with the file's name, and the hook's owner keeps its old data. Saves of
// several files in one poll make one scenario reload.
//
// The emitter and binding owners wire themselves in with, e.g.:
//   reload.addHook(ModFileKind::Emitter, [&](const std::string& path, const std::string& rel) {
//     return emitters.reloadFile(path);  // Status
//   });
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/file_watch.h"
#include "core/result.h"

namespace tumble::script {

class ScenarioHost;

enum class ModFileKind { Manifest, Scenario, Vehicle, Emitter, Bindings, Library };
/// Kind of a file from its path inside the mod ("emitters/smoke.lua").
ModFileKind classifyModFile(const std::string& relPath);
const char* modFileKindName(ModFileKind kind);

struct ReloadEvent {
  std::string file;  ///< path inside the mod
  ModFileKind kind = ModFileKind::Library;
  bool ok = true;
  std::string message;  ///< what happened, for the HUD ("scenarios/x.lua reloaded")
};

class HotReload {
 public:
  /// path: absolute file; relPath: inside the mod (forward slashes).
  using Hook = std::function<Status(const std::string& path, const std::string& relPath)>;

  explicit HotReload(ScenarioHost& host, double period_s = FileWatch::kDefaultPeriod_s);
  /// Adds a hook for one kind of file; several hooks per kind run in order.
  void addHook(ModFileKind kind, Hook hook);
  /// Checks for saved files if the period passed (now_s: a wall clock, s) and
  /// applies them; time_s and step are the simulation's, for on_reload's ctx.
  std::vector<ReloadEvent> poll(double now_s, double time_s, std::int64_t step);
  /// Checks now, whatever the period (tests, a "reload" button).
  std::vector<ReloadEvent> pollNow(double time_s, std::int64_t step);

 private:
  std::vector<ReloadEvent> apply(const std::vector<FileChange>& changes, double time_s, std::int64_t step);

  ScenarioHost& m_host;
  FileWatch m_watch;
  std::string m_root;
  std::map<ModFileKind, std::vector<Hook>> m_hooks;
};

}  // namespace tumble::script
