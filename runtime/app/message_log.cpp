#include "app/message_log.h"

#include <algorithm>

namespace tumble::app {

float messageAlpha(double start_s, double end_s, double time_s, double fade_s) {
  if (time_s < start_s - 1e-9 || time_s >= end_s) return 0;
  if (fade_s <= 0) return 1;
  return float(std::clamp((end_s - time_s) / fade_s, 0.0, 1.0));
}

void MessageLog::update(const script::ScenarioHost& host, double time_s) {
  const auto& errors = host.errors();
  for (; m_seenErrors < errors.size(); ++m_seenErrors)
    m_errors.push_back({errors[m_seenErrors].summary(), time_s, time_s + kErrorSeconds});
  // Keep the list short: only the ones still shown.
  m_errors.erase(std::remove_if(m_errors.begin(), m_errors.end(), [&](const Timed& t) { return t.end_s <= time_s; }),
                 m_errors.end());
}

std::vector<HudMessage> MessageLog::visible(const script::ScenarioHost& host, double time_s) const {
  using script::MessageKind;
  std::vector<HudMessage> out;
  if (host.outcome() != script::Outcome::None)
    out.push_back({std::string(host.outcome() == script::Outcome::Won ? "WON: " : "LOST: ") + host.outcomeReason(),
                   host.outcome() == script::Outcome::Won ? MessageKind::Info : MessageKind::Warning, 1});
  if (host.hasScore()) out.push_back({"score: " + std::to_string(host.score()), MessageKind::Info, 1});
  for (const script::GameMessage& m : host.messages()) {
    const float a = messageAlpha(m.time_s, m.time_s + m.duration_s, time_s, kFade_s);
    if (a > 0) out.push_back({m.text, m.kind, a});
  }
  for (const Timed& e : m_errors) {
    const float a = messageAlpha(e.start_s, e.end_s, time_s, kFade_s);
    if (a > 0) out.push_back({e.text, MessageKind::Error, a});
  }
  for (const std::string& line : host.hudText()) out.push_back({line, MessageKind::Info, 1});
  return out;
}

}  // namespace tumble::app
