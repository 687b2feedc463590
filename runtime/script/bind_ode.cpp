// Lua table `ode` and type OdeSystem: generic ODE systems y' = f(t, y)
// defined in Lua and stepped in double by any numerics integrator
// (numerics/integrator.h); and draw_line, for drawing them.
//
//   local pendulum = ode.system{state = {1.0, 0.0}, method = "rk4",
//     derivative = function(t, y) return {y[2], -9.81 / 2 * math.sin(y[1])} end}
//   pendulum:step(1 / 60)
//
// Cost: every derivative evaluation is a Lua call that builds the state
// table and reads the result table back. tools/bench/bench_numerics.cpp
// measures it (BM_OdeRk4Lua against BM_OdeRk4Cpp): 0.29 us per call for a
// 2-dimensional state against 0.022 us in C++ (2026-11-22, CPU time; the
// README's integrator table). It is fine for the few degrees of freedom of
// a reduced-coordinate model; a rope of 100 particles belongs in C++
// (deformable.h).
//
// Errors inside a Lua derivative never cross the C++ integrator with a
// longjmp: the call is protected, the error becomes a C++ exception that
// unwinds the integrator, and guarded<> raises it in the calling script.
// The state is committed only after a step succeeded.
#include <chrono>
#include <cmath>
#include <limits>
#include <new>

#include "numerics/integrator.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module ode
/// Generic ODE systems for reduced-coordinate (Lagrangian) models: write
/// the state vector and its derivative in Lua, pick an integrator, step it.
/// Computed in double. Draw the result with kinematic bodies
/// (Body:set_position) or draw_line.

namespace {

constexpr const char* kOdeMeta = "tumble.OdeSystem";

/// The Lua functions of one system, called through the registry.
class LuaOde {
 public:
  lua_State* L = nullptr;
  int derivativeRef = LUA_NOREF, jacobianRef = LUA_NOREF, energyRef = LUA_NOREF;
  int dim = 0;
  mutable long derivativeCalls = 0, jacobianCalls = 0;
  mutable double luaSeconds = 0;

  void derivative(double t, const Eigen::VectorXd& y, Eigen::Ref<Eigen::VectorXd> dy) const {
    const auto start = std::chrono::steady_clock::now();
    ++derivativeCalls;
    lua_rawgeti(L, LUA_REGISTRYINDEX, derivativeRef);
    lua_pushnumber(L, t);
    pushVector(y);
    call(2, "derivative");
    readVector(-1, dy, "derivative");
    lua_pop(L, 1);
    luaSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  bool jacobian(double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) const {
    if (jacobianRef == LUA_NOREF) return false;
    ++jacobianCalls;
    lua_rawgeti(L, LUA_REGISTRYINDEX, jacobianRef);
    lua_pushnumber(L, t);
    pushVector(y);
    call(2, "jacobian");
    if (!lua_istable(L, -1)) fail("jacobian must return a table of " + std::to_string(dim) + " rows");
    for (int r = 0; r < dim; ++r) {
      lua_rawgeti(L, -1, r + 1);
      Eigen::VectorXd row(dim);
      readVector(-1, row, "jacobian row " + std::to_string(r + 1));
      J.row(r) = row.transpose();
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return true;
  }

  std::optional<double> energy(const Eigen::VectorXd& y) const {
    if (energyRef == LUA_NOREF) return std::nullopt;
    lua_rawgeti(L, LUA_REGISTRYINDEX, energyRef);
    pushVector(y);
    call(1, "energy");
    if (!lua_isnumber(L, -1)) fail("energy must return a number");
    const double e = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return e;
  }

  void pushVector(const Eigen::VectorXd& y) const {
    lua_createtable(L, dim, 0);
    for (int i = 0; i < dim; ++i) {
      lua_pushnumber(L, y[i]);
      lua_rawseti(L, -2, i + 1);
    }
  }

  void readVector(int idx, Eigen::Ref<Eigen::VectorXd> out, const std::string& what) const {
    idx = lua_absindex(L, idx);
    if (!lua_istable(L, idx)) fail(what + " must return a table of " + std::to_string(dim) + " numbers");
    for (int i = 0; i < dim; ++i) {
      lua_rawgeti(L, idx, i + 1);
      int ok = 0;
      const double v = lua_tonumberx(L, -1, &ok);
      lua_pop(L, 1);
      if (!ok || !std::isfinite(v))
        fail(what + ": entry " + std::to_string(i + 1) + " of " + std::to_string(dim) +
             " is missing or not a finite number");
      out[i] = v;
    }
  }

 private:
  void call(int nargs, const char* what) const {
    if (lua_pcall(L, nargs, 1, 0) != LUA_OK) {
      std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error object is not a string)";
      lua_pop(L, 1);
      fail(std::string(what) + ": " + msg);
    }
  }
  [[noreturn]] static void fail(const std::string& msg) { throw LuaArgError("ode system " + msg); }
};

class FirstOrder final : public numerics::OdeSystem {
 public:
  explicit FirstOrder(const LuaOde& f) : m_f(f) {}
  int dimension() const override { return m_f.dim; }
  void derivative(double t, const Eigen::VectorXd& y, Eigen::VectorXd& dy) const override { m_f.derivative(t, y, dy); }
  bool analyticJacobian(double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J) const override {
    return m_f.jacobian(t, y, J);
  }
  std::optional<double> energy(const Eigen::VectorXd& y) const override { return m_f.energy(y); }

 private:
  const LuaOde& m_f;
};

/// y = [q, v]: the symplectic methods take the second half of the
/// derivative as the acceleration (the first half must be v).
class SecondOrder final : public numerics::SecondOrderSystem {
 public:
  explicit SecondOrder(const LuaOde& f) : m_f(f), m_y(f.dim), m_dy(f.dim) {}
  int dofs() const override { return m_f.dim / 2; }
  void acceleration(double t, ConstRef q, ConstRef v, Ref a) const override {
    m_y << q, v;
    m_f.derivative(t, m_y, m_dy);
    a = m_dy.tail(m_f.dim / 2);
  }
  std::optional<double> energy(const Eigen::VectorXd& y) const override { return m_f.energy(y); }

 private:
  const LuaOde& m_f;
  mutable Eigen::VectorXd m_y, m_dy;
};

struct OdeObject {
  LuaOde f;
  numerics::Method method = numerics::Method::Rk4;
  std::unique_ptr<numerics::OdeSystem> system;
  std::unique_ptr<numerics::Integrator> integrator;
  Eigen::VectorXd y, trial;
  double t = 0;
  long steps = 0, newtonFailures = 0;
};

/// Every ode.system by its number (ScenarioHost::noteOdeSystem), weakly
/// held: a system the script dropped goes with the garbage collector.
char kOdeRegistryKey;
void pushOdeRegistry(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kOdeRegistryKey) == LUA_TTABLE) return;
  lua_pop(L, 1);
  lua_newtable(L);
  lua_createtable(L, 0, 1);
  lua_pushliteral(L, "v");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_pushvalue(L, -1);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kOdeRegistryKey);
}

/// System number n if it is alive, else null.
OdeObject* odeByNumber(lua_State* L, int n) {
  pushOdeRegistry(L);
  lua_rawgeti(L, -1, n);
  auto* o = static_cast<OdeObject*>(luaL_testudata(L, -1, kOdeMeta));
  lua_pop(L, 2);
  return o && o->integrator ? o : nullptr;
}

OdeObject& checkOde(lua_State* L, int idx) {
  auto* o = static_cast<OdeObject*>(luaL_testudata(L, idx, kOdeMeta));
  if (!o || !o->integrator) throw LuaArgError(std::string("expected an OdeSystem, got ") + luaL_typename(L, idx));
  return *o;
}

int optFunctionRef(lua_State* L, const char* key, bool required) {
  const int type = rawGetField(L, 1, key);
  if (type == LUA_TNIL && !required) {
    lua_pop(L, 1);
    return LUA_NOREF;
  }
  if (type != LUA_TFUNCTION) {
    std::string got = luaL_typename(L, -1);
    lua_pop(L, 1);
    throw LuaArgError(std::string("ode.system: field '") + key + "' must be a function" +
                      (required ? " (required)" : "") + ", got " + got);
  }
  return luaL_ref(L, LUA_REGISTRYINDEX);
}

/// @class OdeSystemDef
/// @field state number[] the initial state vector y (any length >= 1)
/// @field derivative fun(t: number, y: number[]): number[] returns y' (same length)
/// @field jacobian? fun(t: number, y: number[]): number[][] returns df/dy as rows (implicit methods; default: finite differences)
/// @field energy? fun(y: number[]): number a conserved quantity, for OdeSystem:energy
/// @field method? string an integrator of ode.methods() (default "rk4"); "symplectic_euler" and "verlet" need state = {q..., v...} with derivative {v..., a...}
/// @field time? number the initial time t (s, default 0)

/// @function ode.system
/// A system y' = f(t, y) stepped in double by a numerics integrator.
/// @param def OdeSystemDef
/// @return OdeSystem the system
/// @example local osc = ode.system{state = {1, 0}, method = "verlet",
/// @example   derivative = function(t, y) return {y[2], -4 * y[1]} end}
int odeSystem(lua_State* L) {
  if (!lua_istable(L, 1))
    throw LuaArgError("ode.system: expected a table, e.g. ode.system{state = {1, 0}, derivative = function(t, y) "
                      "return {y[2], -y[1]} end}");
  lua_settop(L, 1);
  checkFields(L, 1, "ode.system", {"state", "derivative", "jacobian", "energy", "method", "time"});
  if (rawGetField(L, 1, "state") != LUA_TTABLE) throw LuaArgError("ode.system: field 'state' must be a table of numbers");
  const int dim = int(lua_rawlen(L, -1));
  if (dim < 1 || dim > 10000) throw LuaArgError("ode.system: field 'state' must hold 1..10000 numbers");
  Eigen::VectorXd y(dim);
  for (int i = 0; i < dim; ++i) {
    lua_rawgeti(L, -1, i + 1);
    int ok = 0;
    y[i] = lua_tonumberx(L, -1, &ok);
    lua_pop(L, 1);
    if (!ok || !std::isfinite(y[i]))
      throw LuaArgError("ode.system: state[" + std::to_string(i + 1) + "] must be a finite number");
  }
  lua_pop(L, 1);
  const std::string methodName = optStringField(L, 1, "method", "rk4");
  auto method = numerics::parseMethod(methodName);
  if (!method) throw LuaArgError("ode.system: field 'method': " + method.error());
  const bool second = numerics::methodInfo(*method).needsSecondOrder;
  if (second && dim % 2 != 0)
    throw LuaArgError("ode.system: method \"" + methodName + "\" needs state = {q..., v...} (an even length), got " +
                      std::to_string(dim) + " numbers");
  const double t0 = optNumberField(L, 1, "time", 0.0);

  const int number = ScenarioHost::from(L)->noteOdeSystem();
  auto* o = static_cast<OdeObject*>(lua_newuserdatauv(L, sizeof(OdeObject), 0));
  new (o) OdeObject();
  luaL_setmetatable(L, kOdeMeta);
  const int self = lua_gettop(L);
  pushOdeRegistry(L);
  lua_pushvalue(L, self);
  lua_rawseti(L, -2, number);
  lua_pop(L, 1);
  o->f.L = L;
  o->f.dim = dim;
  o->f.derivativeRef = optFunctionRef(L, "derivative", true);
  o->f.jacobianRef = optFunctionRef(L, "jacobian", false);
  o->f.energyRef = optFunctionRef(L, "energy", false);
  o->method = *method;
  if (second) o->system = std::make_unique<SecondOrder>(o->f);
  else o->system = std::make_unique<FirstOrder>(o->f);
  o->integrator = std::make_unique<numerics::Integrator>(*method, dim);
  o->y = y;
  o->t = t0;
  lua_settop(L, self);
  return 1;
}

/// @function ode.methods
/// @return string[] every integrator name, in report order
int odeMethods(lua_State* L) {
  const auto table = numerics::methodTable();
  lua_createtable(L, int(table.size()), 0);
  for (std::size_t i = 0; i < table.size(); ++i) {
    lua_pushstring(L, table[i].name);
    lua_rawseti(L, -2, lua_Integer(i + 1));
  }
  return 1;
}

/// @class OdeSystem
/// A system made by ode.system.

/// @function OdeSystem:step
/// Advances the state by dt, in n equal steps.
/// @param dt number seconds (> 0)
/// @param n? integer steps (default 1)
/// @return OdeSystem the system (for chaining)
int odeStep(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  const double dt = checkNumber(L, 2, "dt");
  const double n = lua_isnoneornil(L, 3) ? 1 : checkNumber(L, 3, "n");
  if (!(dt > 0)) throw LuaArgError("OdeSystem:step: dt must be > 0 seconds");
  if (n != std::floor(n) || n < 1 || n > 1e6) throw LuaArgError("OdeSystem:step: n must be an integer in 1..1e6");
  const double h = dt / n;
  ScenarioHost* host = ScenarioHost::from(L);
  if (host && host->options().freezeSimulation) {  // run --freeze: nothing advances
    lua_settop(L, 1);
    return 1;
  }
  o.f.L = L;  // the running thread (a coroutine may step the system)
  o.trial = o.y;
  double t = o.t;
  for (long i = 0; i < long(n); ++i, t += h) {
    const numerics::StepInfo info = o.integrator->step(*o.system, t, o.trial, h);
    if (!info.converged) ++o.newtonFailures;
  }
  o.y = o.trial;  // committed only when every step succeeded
  if (host && host->takeNanInjection()) o.y[0] = std::numeric_limits<double>::quiet_NaN();  // run --inject-nan
  o.t += dt;
  o.steps += long(n);
  lua_settop(L, 1);
  return 1;
}

/// @function OdeSystem:state
/// @return number[] a copy of the state vector
int odeState(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  o.f.pushVector(o.y);
  return 1;
}

/// @function OdeSystem:set_state
/// Replaces the state (same length), e.g. after a kick.
/// @param y number[]
int odeSetState(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  Eigen::VectorXd y(o.f.dim);
  if (!lua_istable(L, 2)) throw LuaArgError("OdeSystem:set_state: expected a table of " + std::to_string(o.f.dim) + " numbers");
  for (int i = 0; i < o.f.dim; ++i) {
    lua_rawgeti(L, 2, i + 1);
    int ok = 0;
    y[i] = lua_tonumberx(L, -1, &ok);
    lua_pop(L, 1);
    if (!ok || !std::isfinite(y[i]))
      throw LuaArgError("OdeSystem:set_state: entry " + std::to_string(i + 1) + " must be a finite number");
  }
  o.y = y;
  return 0;
}

/// @function OdeSystem:get
/// @param i integer index into the state (from 1)
/// @return number y[i]
int odeGet(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  const double i = checkNumber(L, 2, "index");
  if (i != std::floor(i) || i < 1 || i > o.f.dim)
    throw LuaArgError("OdeSystem:get: index must be an integer in 1.." + std::to_string(o.f.dim));
  lua_pushnumber(L, o.y[int(i) - 1]);
  return 1;
}

/// @function OdeSystem:time
/// @return number the system's time t (s)
int odeTime(lua_State* L) {
  lua_pushnumber(L, checkOde(L, 1).t);
  return 1;
}

/// @function OdeSystem:energy
/// @return number? the def's energy(y) now, nil without one
int odeEnergy(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  o.f.L = L;
  auto e = o.f.energy(o.y);
  if (e) lua_pushnumber(L, *e);
  else lua_pushnil(L);
  return 1;
}

/// @function OdeSystem:stats
/// What stepping cost so far.
/// @return table {steps, derivative_calls, jacobian_calls, newton_failures, lua_seconds, method}
int odeStats(lua_State* L) {
  OdeObject& o = checkOde(L, 1);
  lua_createtable(L, 0, 6);
  lua_pushinteger(L, o.steps);
  rawSetField(L, -2, "steps");
  lua_pushinteger(L, o.f.derivativeCalls);
  rawSetField(L, -2, "derivative_calls");
  lua_pushinteger(L, o.f.jacobianCalls);
  rawSetField(L, -2, "jacobian_calls");
  lua_pushinteger(L, o.newtonFailures);
  rawSetField(L, -2, "newton_failures");
  lua_pushnumber(L, o.f.luaSeconds);
  rawSetField(L, -2, "lua_seconds");
  lua_pushstring(L, numerics::methodName(o.method));
  rawSetField(L, -2, "method");
  return 1;
}

int odeGc(lua_State* L) {
  auto* o = static_cast<OdeObject*>(luaL_testudata(L, 1, kOdeMeta));
  if (!o || !o->integrator) return 0;
  for (int ref : {o->f.derivativeRef, o->f.jacobianRef, o->f.energyRef})
    if (ref != LUA_NOREF) luaL_unref(L, LUA_REGISTRYINDEX, ref);
  o->~OdeObject();
  return 0;
}

int odeToString(lua_State* L) {
  auto* o = static_cast<OdeObject*>(luaL_checkudata(L, 1, kOdeMeta));
  lua_pushfstring(L, "OdeSystem(%d, %s)", o->f.dim, numerics::methodName(o->method));
  return 1;
}

/// @function draw_line
/// Draws a line this frame (cleared before each on_update): a rod, a
/// wire, a trajectory. At most 65536 lines per frame.
/// @param a Vec3Arg one end (m)
/// @param b Vec3Arg the other end (m)
/// @param color? Vec3Arg linear RGB 0..1 (default yellow)
int drawLine(lua_State* L) {
  ScriptLine line;
  line.a_m = checkVec3(L, 1, "draw_line a");
  line.b_m = checkVec3(L, 2, "draw_line b");
  line.color = lua_isnoneornil(L, 3) ? Eigen::Vector3f(1, 1, 0) : checkVec3(L, 3, "draw_line color").cast<float>();
  if (ScenarioHost* host = ScenarioHost::from(L)) host->presentation().addScriptLine(line);
  return 0;
}

const luaL_Reg kOde[] = {
    {"system", guarded<odeSystem>},
    {"methods", guarded<odeMethods>},
    {nullptr, nullptr},
};
const luaL_Reg kMethods[] = {
    {"step", guarded<odeStep>},   {"state", guarded<odeState>}, {"set_state", guarded<odeSetState>},
    {"get", guarded<odeGet>},     {"time", guarded<odeTime>},   {"energy", guarded<odeEnergy>},
    {"stats", guarded<odeStats>}, {nullptr, nullptr},
};
const luaL_Reg kGlobals[] = {
    {"draw_line", guarded<drawLine>},
    {nullptr, nullptr},
};

}  // namespace

void saveOdeSystems(lua_State* L, int made, ByteWriter& w) {
  w.pod(std::int32_t(made));
  for (int n = 1; n <= made; ++n) {
    const OdeObject* o = odeByNumber(L, n);
    w.pod(std::uint8_t(o != nullptr));
    if (!o) continue;
    w.pod(std::int32_t(o->f.dim));
    w.pod(std::int32_t(o->method));
    w.vec(std::vector<double>(o->y.data(), o->y.data() + o->y.size()));
    w.pod(o->t);
    w.pod(std::int64_t(o->steps));
    w.pod(std::int64_t(o->newtonFailures));
    o->integrator->saveState(w);
  }
}

Status restoreOdeSystems(lua_State* L, int made, ByteReader& r, bool apply) {
  const auto saved = r.pod<std::int32_t>();
  if (!r.ok() || saved < 0) return makeError("damaged (ode systems)");
  // Read and checked whole, then applied: a refused restore changes nothing.
  struct Saved {
    OdeObject* o;
    Eigen::VectorXd y;
    double t;
    std::int64_t steps, newtonFailures;
    std::string integrator;
  };
  std::vector<Saved> all;
  for (int n = 1; n <= saved; ++n) {
    if (!r.pod<std::uint8_t>()) continue;
    const auto dim = r.pod<std::int32_t>();
    const auto method = r.pod<std::int32_t>();
    const std::vector<double> y = r.vec<double>(10000);
    Saved s{nullptr, {}, r.pod<double>(), r.pod<std::int64_t>(), r.pod<std::int64_t>(), {}};
    if (!r.ok() || dim < 1 || dim > 10000 || y.size() != std::size_t(dim) || method < 0 ||
        method > std::int32_t(numerics::Method::Sdirk2))
      return makeError("damaged (ode.system number " + std::to_string(n) + ")");
    // The integrator's part, checked on a scratch integrator first.
    const std::size_t start = r.position();
    numerics::Integrator scratch(numerics::Method(method), dim);
    if (!scratch.restoreState(r)) return makeError("damaged (ode.system number " + std::to_string(n) + ")");
    s.integrator = r.bytesFrom(start);
    if (n > made)
      return makeError("ode.system number " + std::to_string(n) +
                       " is in the snapshot but was made after on_start (a snapshot holds its numbers, not its Lua "
                       "functions)");
    // Made by on_start but collected here since: nothing can reach it.
    s.o = odeByNumber(L, n);
    if (!s.o) continue;
    if (dim != s.o->f.dim || method != std::int32_t(s.o->method))
      return makeError("ode.system number " + std::to_string(n) + ": the snapshot's has another size or method");
    s.y = Eigen::Map<const Eigen::VectorXd>(y.data(), Eigen::Index(y.size()));
    all.push_back(std::move(s));
  }
  if (!apply) return Ok{};
  for (Saved& s : all) {
    s.o->y = s.y;
    s.o->t = s.t;
    s.o->steps = long(s.steps);
    s.o->newtonFailures = long(s.newtonFailures);
    ByteReader ir(s.integrator);
    s.o->integrator->restoreState(ir);
  }
  return Ok{};
}

void openOdeBindings(lua_State* L, int envIndex) {
  registerType(L, {kOdeMeta, kMethods, odeToString, nullptr, odeGc});
  registerModule(L, envIndex, "ode", kOde);
  registerFunctions(L, envIndex, kGlobals);
}

}  // namespace tumble::script
