// The Lua part of a snapshot of a running scene (app/scene_state.h,
// docs/snapshots.md). C++ cannot store Lua closures or locals, so a snapshot
// keeps what it can keep exactly and the rule for the rest is the hot
// reload's:
//   - ctx.state, as plain data (nil, booleans, numbers with their exact
//     bits, strings, tables of those, and Body handles), no cycles, at most
//     kMaxDepth deep;
//   - the timers' schedule (due times, periods, order), the scenario's
//     random generator, math.random's state, random.new()'s seed counter;
//   - game state (score, outcome, messages) and the expectations so far;
//   - every ode.system's state vector, time and integrator memory, by the
//     number it was made with (bind_ode.cpp: on_start makes them again);
//   - the trigger volumes on_start made: which bodies are inside each
//     (their callbacks are on_start's again), and which were removed since;
//   - what is seen (Presentation::saveState): body, rope and cloth colours,
//     ground textures, models on bodies and static models (files as
//     "MOD:path"), the camera, the sky and the lap display, so that a body
//     made after on_start keeps its colour and model, and a camera or sky
//     set in on_update stays, as in the run without a split.
// Loading runs on_start again (it re-makes the bodies, locals and timers as
// at the start), then puts the saved state back. A scenario with on_reload
// owns its timers and triggers, as after a hot reload: they are dropped and
// on_reload(ctx, state) re-makes them. Without on_reload, a timer or a
// trigger volume made after on_start (its function would not exist after
// loading) is refused at save time.
#include <cstring>
#include <filesystem>
#include <set>

#include "core/byte_stream.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

namespace fs = std::filesystem;

namespace {

// 2: ode.system objects' state at the end. 3: the presentation after it.
constexpr std::uint32_t kScriptStateVersion = 3;
constexpr int kMaxDepth = 32;
constexpr std::size_t kMaxNodes = 1'000'000;
constexpr std::size_t kMaxText = std::size_t(64) << 20;

enum class Tag : std::uint8_t { Nil, False, True, Integer, Float, String, Table, Body, End };

struct ValueWriter {
  lua_State* L;
  ByteWriter& w;
  std::set<const void*> path;
  std::size_t nodes = 0;

  Status value(int idx, const std::string& where, int depth) {
    idx = lua_absindex(L, idx);
    if (++nodes > kMaxNodes) return makeError(where + ": more than " + std::to_string(kMaxNodes) + " values");
    physics::BodyId body;
    switch (lua_type(L, idx)) {
      case LUA_TNIL: w.pod(Tag::Nil); return Ok{};
      case LUA_TBOOLEAN: w.pod(lua_toboolean(L, idx) ? Tag::True : Tag::False); return Ok{};
      case LUA_TNUMBER:
        if (lua_isinteger(L, idx)) {
          w.pod(Tag::Integer);
          w.pod(std::int64_t(lua_tointeger(L, idx)));
        } else {
          w.pod(Tag::Float);
          w.pod(double(lua_tonumber(L, idx)));
        }
        return Ok{};
      case LUA_TSTRING: {
        std::size_t n = 0;
        const char* s = lua_tolstring(L, idx, &n);
        w.pod(Tag::String);
        w.text(std::string(s, n));
        return Ok{};
      }
      case LUA_TTABLE: return table(idx, where, depth);
      case LUA_TUSERDATA:
        if (testBody(L, idx, &body)) {
          w.pod(Tag::Body);
          w.pod(body.index);
          w.pod(body.generation);
          return Ok{};
        }
        [[fallthrough]];
      default:
        return makeError(where + " is a " + luaL_typename(L, idx) +
                         ": a snapshot stores plain data (nil, booleans, numbers, strings, tables of them, bodies); "
                         "re-make functions and other objects in on_reload(ctx, state)");
    }
  }

  Status table(int idx, const std::string& where, int depth) {
    if (depth >= kMaxDepth) return makeError(where + ": tables nested more than " + std::to_string(kMaxDepth) + " deep");
    const void* p = lua_topointer(L, idx);
    if (path.count(p)) return makeError(where + ": the table contains itself (a cycle)");
    path.insert(p);
    if (!lua_checkstack(L, 4)) return makeError(where + ": out of Lua stack");
    w.pod(Tag::Table);
    lua_pushnil(L);
    while (lua_next(L, idx) != 0) {
      const int kt = lua_type(L, -2);
      if (kt != LUA_TSTRING && kt != LUA_TNUMBER && kt != LUA_TBOOLEAN) {
        lua_pop(L, 2);
        return makeError(where + " has a " + std::string(lua_typename(L, kt)) + " key: keys must be strings, numbers or booleans");
      }
      std::string key;
      if (kt == LUA_TSTRING) key = "." + std::string(lua_tostring(L, -2));
      else if (kt == LUA_TNUMBER) key = "[" + std::string(lua_isinteger(L, -2) ? std::to_string(lua_tointeger(L, -2)) : "number") + "]";
      else key = "[boolean]";
      if (Status st = value(-2, where + key + " (key)", depth + 1); !st) {
        lua_pop(L, 2);
        return st;
      }
      if (Status st = value(-1, where + key, depth + 1); !st) {
        lua_pop(L, 2);
        return st;
      }
      lua_pop(L, 1);
    }
    w.pod(Tag::End);
    path.erase(p);
    return Ok{};
  }
};

/// Reads one value and pushes it: 1 pushed, 0 the end of a table (nothing
/// pushed), -1 damaged bytes (nothing pushed).
int readValue(lua_State* L, ByteReader& r, int depth, std::size_t& nodes) {
  if (depth > kMaxDepth || ++nodes > kMaxNodes || !lua_checkstack(L, 4)) return -1;
  const Tag tag = r.pod<Tag>();
  if (!r.ok()) return -1;
  switch (tag) {
    case Tag::Nil: lua_pushnil(L); return 1;
    case Tag::False: lua_pushboolean(L, 0); return 1;
    case Tag::True: lua_pushboolean(L, 1); return 1;
    case Tag::Integer: {
      const auto v = r.pod<std::int64_t>();
      if (!r.ok()) return -1;
      lua_pushinteger(L, lua_Integer(v));
      return 1;
    }
    case Tag::Float: {
      const auto v = r.pod<double>();
      if (!r.ok()) return -1;
      lua_pushnumber(L, v);
      return 1;
    }
    case Tag::String: {
      const std::string v = r.text(kMaxText);
      if (!r.ok()) return -1;
      lua_pushlstring(L, v.data(), v.size());
      return 1;
    }
    case Tag::Body: {
      physics::BodyId id;
      id.index = r.pod<std::uint32_t>();
      id.generation = r.pod<std::uint32_t>();
      if (!r.ok()) return -1;
      pushBody(L, id);
      return 1;
    }
    case Tag::Table: {
      lua_newtable(L);
      for (;;) {
        const int k = readValue(L, r, depth + 1, nodes);
        if (k == 0) return 1;
        if (k < 0 || lua_isnil(L, -1)) {
          lua_pop(L, k < 0 ? 1 : 2);
          return -1;
        }
        if (readValue(L, r, depth + 1, nodes) != 1) {
          lua_pop(L, 2);
          return -1;
        }
        lua_rawset(L, -3);
      }
    }
    case Tag::End: return 0;
  }
  return -1;
}

/// The userdata holding a generator's state: upvalue 1 of `fn` (math.random
/// keeps Lua's xoshiro state there, random.float the scenario's Random).
void* generatorState(lua_State* L, int tableIndex, const char* fn, std::size_t* size) {
  *size = 0;
  if (rawGetField(L, tableIndex, fn) != LUA_TFUNCTION) {
    lua_pop(L, 1);
    return nullptr;
  }
  void* p = nullptr;
  if (lua_getupvalue(L, -1, 1)) {
    if (lua_type(L, -1) == LUA_TUSERDATA) {
      p = lua_touserdata(L, -1);  // stays alive: the function holds it
      *size = lua_rawlen(L, -1);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return p;
}

}  // namespace

std::string ScenarioHost::modRelative(const std::string& where) const {
  const std::string dir = m_mod.dir + "/";
  return where.rfind(dir, 0) == 0 ? where.substr(dir.size()) : where;
}

bool ScenarioHost::hasOnReload() {
  lua_State* L = m_vm.state();
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_scenarioRef);
  const bool has = rawGetField(L, -1, "on_reload") == LUA_TFUNCTION;
  lua_pop(L, 2);
  return has;
}

Result<std::string> ScenarioHost::saveState() {
  lua_State* L = m_vm.state();
  const bool ownsTimers = hasOnReload();
  if (!ownsTimers) {
    if (m_triggers.anyFrom(m_firstTriggerAfterStart))
      return makeError(m_file + ": a trigger volume was made after on_start, and a snapshot cannot store its "
                       "callbacks; give the scenario an on_reload(ctx, state) that re-makes its triggers");
    for (const TimerQueue::Schedule& t : m_timers.schedule())
      if (t.id >= m_firstTimerAfterStart)
        return makeError(m_file + ": the timer whose function is defined at " + modRelative(m_timers.definedAt(t.id)) +
                         " was made after on_start, and a snapshot cannot store its function; give the scenario an "
                         "on_reload(ctx, state) that re-makes it from ctx.state");
  }
  ByteWriter w;
  w.pod(kScriptStateVersion);
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_ctxRef);
  rawGetField(L, -1, "state");
  ValueWriter vw{L, w, {}, 0};
  Status st = vw.value(-1, "ctx.state", 0);
  lua_pop(L, 2);
  if (!st) return makeError(m_file + ": " + st.error());
  w.pod(std::uint8_t(ownsTimers));
  std::vector<TimerQueue::Schedule> timers = ownsTimers ? std::vector<TimerQueue::Schedule>{} : m_timers.schedule();
  w.vec(timers);
  w.pod(m_timers.nextId());
  w.pod(m_timers.nextSeq());
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_envRef);
  const int env = lua_gettop(L);
  for (const auto& [table, fn] : {std::pair{"math", "random"}, std::pair{"random", "float"}}) {
    std::size_t n = 0;
    void* p = nullptr;
    if (rawGetField(L, env, table) == LUA_TTABLE) p = generatorState(L, lua_gettop(L), fn, &n);
    lua_pop(L, 1);
    w.text(p ? std::string(static_cast<const char*>(p), n) : std::string());
  }
  lua_pop(L, 1);
  w.pod(m_randomCount);
  w.pod(m_score);
  w.pod(std::uint8_t(m_hasScore));
  w.pod(std::int32_t(m_outcome));
  w.text(m_outcomeReason);
  w.pod(m_outcomeTime_s);
  w.pod(std::uint64_t(m_messages.size()));
  for (const GameMessage& m : m_messages) {
    w.text(m.text);
    w.pod(m.time_s);
    w.pod(m.duration_s);
    w.pod(std::int32_t(m.kind));
  }
  w.pod(std::uint64_t(m_expectations.size()));
  for (const Expectation& e : m_expectations) {
    w.text(e.name);
    w.pod(std::uint8_t(e.ok));
    w.pod(std::uint8_t(e.isBool));
    w.pod(e.value);
    w.pod(std::uint8_t(e.min.has_value()));
    w.pod(e.min.value_or(0));
    w.pod(std::uint8_t(e.max.has_value()));
    w.pod(e.max.value_or(0));
  }
  saveOdeSystems(L, m_odeSystemsMade, w);
  if (!ownsTimers) m_triggers.saveState(w);
  // Model files as "MOD:path": every one came through resolveModFile, so it
  // lies inside one of the mods' folders.
  std::vector<std::pair<std::string, fs::path>> roots;
  for (const auto& [name, dir] : m_options.modDirs) roots.emplace_back(name, fs::weakly_canonical(fs::path(dir)));
  m_presentation.saveState(w, [&](const std::string& file) {
    for (const auto& [name, root] : roots) {
      const fs::path rel = fs::path(file).lexically_relative(root);
      if (!rel.empty() && *rel.begin() != "..") return name + ":" + rel.generic_string();
    }
    return file;  // not inside a mod: refused when loading
  });
  return w.take();
}

Status ScenarioHost::restoreState(const std::string& bytes, double time_s, std::int64_t step) {
  lua_State* L = m_vm.state();
  const int top = lua_gettop(L);
  ByteReader r(bytes);
  if (const auto v = r.pod<std::uint32_t>(); !r.ok() || v != kScriptStateVersion)
    return makeError("script state: version " + std::to_string(v) + ", this build reads " +
                     std::to_string(kScriptStateVersion));
  std::size_t nodes = 0;
  if (readValue(L, r, 0, nodes) != 1) return makeError("script state: ctx.state is damaged");
  const int state = lua_gettop(L);
  auto fail = [&](const std::string& what) {
    lua_settop(L, top);
    return makeError("script state: " + what);
  };
  const bool ownsTimers = r.pod<std::uint8_t>() != 0;
  const auto timers = r.vec<TimerQueue::Schedule>(TimerQueue::kMaxPending);
  const auto nextId = r.pod<std::uint32_t>();
  const auto nextSeq = r.pod<std::uint64_t>();
  std::string generators[2];
  for (std::string& g : generators) g = r.text(1024);
  const auto randomCount = r.pod<std::uint64_t>();
  const auto score = r.pod<double>();
  const bool hasScore = r.pod<std::uint8_t>() != 0;
  const auto outcome = r.pod<std::int32_t>();
  std::string reason = r.text(kMaxText);
  const auto outcomeTime = r.pod<double>();
  std::vector<GameMessage> messages(std::size_t(std::min<std::uint64_t>(r.pod<std::uint64_t>(), kMaxMessages + 1)));
  if (messages.size() > kMaxMessages) return fail("damaged (messages)");
  for (GameMessage& m : messages) {
    m.text = r.text(kMaxText);
    m.time_s = r.pod<double>();
    m.duration_s = r.pod<double>();
    const auto kind = r.pod<std::int32_t>();
    if (kind < 0 || kind > 2) return fail("damaged (message kind)");
    m.kind = MessageKind(kind);
  }
  const auto expectationCount = r.pod<std::uint64_t>();
  if (!r.ok() || expectationCount > kMaxNodes || expectationCount > r.remaining() / sizeof(double))
    return fail("damaged (truncated)");
  std::vector<Expectation> expectations(expectationCount);
  for (Expectation& e : expectations) {
    e.name = r.text(kMaxText);
    e.ok = r.pod<std::uint8_t>() != 0;
    e.isBool = r.pod<std::uint8_t>() != 0;
    e.value = r.pod<double>();
    const bool hasMin = r.pod<std::uint8_t>() != 0;
    const auto mn = r.pod<double>();
    const bool hasMax = r.pod<std::uint8_t>() != 0;
    const auto mx = r.pod<double>();
    if (hasMin) e.min = mn;
    if (hasMax) e.max = mx;
  }
  if (!r.ok()) return fail("damaged (truncated)");
  // Every part is read and checked before any is applied: a refused state
  // changes nothing (the ODE systems and triggers are read again below).
  // Before, a damaged state whose trigger part was whole removed the
  // triggers it did not hold and was then refused for bytes further on,
  // and the scene could not go back even to a state saved from itself
  // (found by the snapshot fuzzer).
  const std::size_t odeStart = r.position();
  if (Status st = restoreOdeSystems(L, m_odeSystemsMade, r, false); !st) return fail(st.error());
  const std::string odeBytes = r.bytesFrom(odeStart);
  const std::size_t triggersStart = r.position();
  if (!ownsTimers)
    if (Status st = m_triggers.restoreState(r, world().bodySlotCount(), false); !st) return fail(st.error());
  const std::string triggerBytes = r.bytesFrom(triggersStart);
  Presentation presentation = m_presentation;
  Status seen = presentation.restoreState(
      r, [&](const std::string& ref) { return resolveModFile(ref, m_mod, m_options.modDirs); },
      // A body slot of this world: a model may stay attached to a body
      // removed since (it is not drawn), a camera may follow one.
      [&](physics::BodyId id) { return id.index < world().bodySlotCount(); }, world().bodySlotCount());
  if (!seen) return fail(seen.error());
  if (!r.ok() || !r.atEnd()) return fail("damaged (truncated or bytes after the end)");
  if (outcome < int(Outcome::None) || outcome > int(Outcome::Lost)) return fail("damaged (outcome)");
  if (ownsTimers != hasOnReload())
    return fail(ownsTimers ? "saved by a scenario with on_reload, this one has none"
                           : "saved by a scenario without on_reload, this one has one");
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_envRef);
  const int env = lua_gettop(L);
  const std::pair<const char*, const char*> gens[] = {{"math", "random"}, {"random", "float"}};
  void* generatorAt[2] = {nullptr, nullptr};
  for (int i = 0; i < 2; ++i) {
    std::size_t n = 0;
    void* p = nullptr;
    if (rawGetField(L, env, gens[i].first) == LUA_TTABLE) p = generatorState(L, lua_gettop(L), gens[i].second, &n);
    lua_pop(L, 1);
    if (p && n == generators[i].size()) generatorAt[i] = p;
    else if (p || !generators[i].empty()) return fail(std::string(gens[i].first) + "." + gens[i].second +
                                                      ": the generator differs from the saved one");
  }
  // The last check; restoreSchedule changes nothing when it refuses.
  if (!ownsTimers && !m_timers.restoreSchedule(timers, nextId, nextSeq))
    return fail("a timer the snapshot holds was not made by on_start here (the scenario file changed?)");
  // Applied: nothing below is refused.
  for (int i = 0; i < 2; ++i)
    if (generatorAt[i]) std::memcpy(generatorAt[i], generators[i].data(), generators[i].size());
  {
    ByteReader again(odeBytes);
    (void)restoreOdeSystems(L, m_odeSystemsMade, again);
  }
  if (!ownsTimers) {
    ByteReader again(triggerBytes);
    (void)m_triggers.restoreState(again, world().bodySlotCount());
  }
  lua_rawgeti(L, LUA_REGISTRYINDEX, m_ctxRef);
  lua_pushvalue(L, state);
  rawSetField(L, -2, "state");
  m_randomCount = randomCount;
  m_score = score;
  m_hasScore = hasScore;
  m_outcome = Outcome(outcome);
  m_outcomeReason = std::move(reason);
  m_outcomeTime_s = outcomeTime;
  m_messages = std::move(messages);
  m_expectations = std::move(expectations);
  m_presentation = std::move(presentation);
  lua_settop(L, top);
  m_now_s = time_s;
  if (ownsTimers) {  // as after a hot reload: the scenario re-makes its timers and triggers
    m_timers.clear();
    m_triggers.clear();
    pushCtx(time_s, 0, step);
    rawGetField(L, -1, "state");
    const std::size_t before = m_errors.size();
    if (!callLifecycle("on_reload", 2, nullptr, nullptr) && m_errors.size() > before)
      return makeError(m_errors.back().summary());
  }
  return Ok{};
}

}  // namespace tumble::script
