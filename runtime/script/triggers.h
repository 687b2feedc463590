#pragma once
// Trigger boxes of one scenario (trigger.box; bind_trigger.cpp): boxes,
// axis-aligned or turned by an orientation, that report non-static bodies
// whose centre of mass enters or leaves them. The host updates them among the after-step
// callbacks: first every trigger's new set of bodies (in body index order,
// compared with the last step's: enters and exits), then the callbacks,
// after every trigger is updated, since callbacks may add or remove
// triggers and bodies.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/byte_stream.h"
#include "core/math.h"
#include "core/result.h"
#include "physics/body.h"

struct lua_State;

namespace tumble::physics {
class World;
}

namespace tumble::script {

class TriggerSet {
 public:
  explicit TriggerSet(lua_State* L) : m_L(L) {}

  /// on_enter / on_exit functions at the given stack indices (0 = none).
  /// Returns the trigger's id (> 0).
  /// The box's half sizes are along its own axes, turned by `orientation`.
  std::uint32_t add(const Vec3& center_m, const Vec3& halfSize_m, const Quat& orientation, int onEnterIdx,
                    int onExitIdx);
  bool remove(std::uint32_t id);
  void clear();
  int liveCount() const { return m_live; }
  /// Bodies inside a trigger after the last step (null for a removed one).
  const std::vector<physics::BodyId>* bodiesIn(std::uint32_t id) const;

  /// Called with the callback's function on top of the stack; it pushes its
  /// arguments (body, trigger) and makes the call.
  using Call = std::function<void(physics::BodyId body, std::uint32_t trigger, bool enter)>;
  /// Updates every trigger against the world, then calls back.
  void update(const physics::World& world, const Call& call);

  /// Id the next trigger gets.
  std::uint32_t nextId() const { return m_nextId; }
  /// Whether a live trigger has an id >= firstId (made after on_start).
  bool anyFrom(std::uint32_t firstId) const;
  /// Snapshots (scenario_state.cpp): each slot's trigger id (0: removed)
  /// and the bodies inside it, and the next id. restoreState goes back into
  /// the triggers on_start made again (their callbacks are theirs): a saved
  /// trigger this set does not have in that slot is refused; triggers
  /// removed since the start are removed again.
  void saveState(ByteWriter& w) const;
  /// apply = false: reads and checks only (nothing changes), so that a
  /// caller can check every part of a state before it applies any.
  Status restoreState(ByteReader& r, std::size_t bodySlots, bool apply = true);

 private:
  struct Trigger {
    std::uint32_t id = 0;  ///< 0: removed slot
    Vec3 center_m = Vec3::Zero(), half_m = Vec3::Zero();
    Quat toBox = Quat::Identity();  ///< world -> the box's axes (the inverse of its orientation)
    int onEnterRef = 0, onExitRef = 0;  ///< registry refs, 0 = none
    std::vector<physics::BodyId> inside, scratch;  ///< sorted by index
  };
  struct Event {
    std::uint32_t trigger;
    physics::BodyId body;
    bool enter;
  };

  lua_State* m_L;
  std::vector<Trigger> m_triggers;
  std::uint32_t m_nextId = 1;
  int m_live = 0;
  std::vector<Event> m_events;  ///< reused each step
};

}  // namespace tumble::script
