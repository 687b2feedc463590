#include "script/hot_reload.h"

#include <filesystem>

#include "script/scenario_host.h"

namespace fs = std::filesystem;

namespace tumble::script {

ModFileKind classifyModFile(const std::string& relPath) {
  auto starts = [&](const char* prefix) { return relPath.rfind(prefix, 0) == 0; };
  if (relPath == "mod.lua") return ModFileKind::Manifest;
  if (relPath == "bindings.lua") return ModFileKind::Bindings;
  if (starts("scenarios/")) return ModFileKind::Scenario;
  if (starts("vehicles/")) return ModFileKind::Vehicle;
  if (starts("emitters/")) return ModFileKind::Emitter;
  return ModFileKind::Library;
}

const char* modFileKindName(ModFileKind kind) {
  switch (kind) {
    case ModFileKind::Manifest: return "manifest";
    case ModFileKind::Scenario: return "scenario";
    case ModFileKind::Vehicle: return "vehicle";
    case ModFileKind::Emitter: return "emitter";
    case ModFileKind::Bindings: return "bindings";
    case ModFileKind::Library: return "library";
  }
  return "?";
}

HotReload::HotReload(ScenarioHost& host, double period_s)
    : m_host(host), m_watch({host.mod().dir}, {".lua"}, period_s),
      m_root(fs::absolute(host.mod().dir).lexically_normal().string()) {}

void HotReload::addHook(ModFileKind kind, Hook hook) { m_hooks[kind].push_back(std::move(hook)); }

std::vector<ReloadEvent> HotReload::poll(double now_s, double time_s, std::int64_t step) {
  auto changes = m_watch.pollIfDue(now_s);
  return changes.empty() ? std::vector<ReloadEvent>{} : apply(changes, time_s, step);
}

std::vector<ReloadEvent> HotReload::pollNow(double time_s, std::int64_t step) {
  return apply(m_watch.poll(), time_s, step);
}

std::vector<ReloadEvent> HotReload::apply(const std::vector<FileChange>& changes, double time_s, std::int64_t step) {
  std::vector<ReloadEvent> events;
  std::vector<std::string> scenarioFiles;  // files that make the scenario reload
  for (const FileChange& c : changes) {
    if (c.kind == FileChange::Kind::Removed) continue;  // nothing to load; the old code stays
    std::string rel = fs::path(c.path).lexically_relative(m_root).generic_string();
    ModFileKind kind = classifyModFile(rel);
    switch (kind) {
      case ModFileKind::Manifest:
        events.push_back({rel, kind, true, rel + " changed: restart the scenario to apply it"});
        break;
      case ModFileKind::Scenario:
        if (rel == m_host.scenarioFile()) scenarioFiles.push_back(rel);
        break;  // another scenario of the mod: not running
      case ModFileKind::Library: scenarioFiles.push_back(rel); break;
      case ModFileKind::Vehicle:
      case ModFileKind::Emitter:
      case ModFileKind::Bindings: {
        auto it = m_hooks.find(kind);
        if (it == m_hooks.end()) break;  // nothing of that kind is live in this scene
        for (const Hook& hook : it->second) {
          Status st = hook(c.path, rel);
          ReloadEvent e{rel, kind, bool(st), st ? rel + " reloaded" : st.error()};
          if (!st) {
            ScriptError err;
            err.mod = m_host.mod().name;
            err.file = rel;
            err.message = "reload failed, the previous " + std::string(modFileKindName(kind)) +
                          " stays: " + st.error();
            m_host.recordError(err);
          }
          events.push_back(std::move(e));
        }
        break;
      }
    }
  }
  if (!scenarioFiles.empty()) {
    Status st = m_host.reload(time_s, step);
    std::string files;
    for (const auto& f : scenarioFiles) files += (files.empty() ? "" : ", ") + f;
    events.push_back({scenarioFiles.front(), ModFileKind::Scenario, bool(st),
                      st ? files + " reloaded" : st.error()});
  }
  return events;
}

}  // namespace tumble::script
