#include "app/tuning.h"

#include "core/log.h"

namespace tumble::app {

void fillTuningPanel(const script::Tunables& tunables, render::TuningPanel& panel) {
  panel.items.resize(tunables.items().size());
  for (std::size_t i = 0; i < tunables.items().size(); ++i) {
    const script::Tunable& t = tunables.items()[i];
    render::TuningItem& item = panel.items[i];
    item.name = t.name;
    item.unit = t.unit;
    item.description = t.description;
    item.kind = t.kind == script::Tunable::Kind::Number ? render::TuningItem::Kind::Number
                : t.kind == script::Tunable::Kind::Bool ? render::TuningItem::Kind::Bool
                                                        : render::TuningItem::Kind::Choice;
    item.value = t.value();
    item.defaultValue = t.defaultValue;
    item.min = t.min;
    item.max = t.max;
    item.step = t.step;
    item.choices = t.choices;
    item.userSet = t.isUserSet();
    item.edited = item.resetRequested = false;
  }
}

void applyTuningPanel(render::TuningPanel& panel, script::Tunables& tunables, const std::string& mod) {
  for (render::TuningItem& item : panel.items) {
    if (item.resetRequested) tunables.reset(item.name);
    else if (item.edited) {
      if (Status st = tunables.set(item.name, item.value); !st) panel.status = st.error();
    }
    item.edited = item.resetRequested = false;
  }
  if (panel.resetAllRequested) {
    tunables.resetAll();
    panel.status = "all values back to the script's defaults (Save to keep that)";
    panel.resetAllRequested = false;
  }
  if (panel.saveRequested) {
    panel.saveRequested = false;
    if (Status st = tunables.saveOverrides(panel.overridesPath, mod); st) {
      panel.status = "saved to " + panel.overridesPath;
      log::info("tuning: " + panel.status);
    } else {
      panel.status = "not saved: " + st.error();
      log::error("tuning: " + panel.status);
    }
  }
}

}  // namespace tumble::app
