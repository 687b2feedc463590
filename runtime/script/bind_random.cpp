// Lua table `random` and type Random: reproducible random numbers.
//
// Generator: xoshiro256** (Blackman and Vigna), seeded through splitmix64 as
// its authors recommend; the same algorithm Lua 5.4 uses for math.random, but
// with its own state per object, so streams do not disturb each other and
// the same seed gives the same numbers on every run and platform (integer
// arithmetic; float() uses the top 53 bits).
#include <cmath>

#include "core/random.h"
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module random
/// Deterministic random numbers. `random.new(seed)` makes an independent
/// generator; the functions random.float, random.int, random.normal,
/// random.chance and random.pick use the scenario's own generator, seeded
/// from the run's --seed. math.random is also seeded from --seed at load, so
/// it is reproducible too, but one stream shared by everything in the
/// scenario; prefer a Random per purpose (spawning, weather, ...) so adding
/// one call does not change every later number.

namespace {

constexpr const char* kRandomMeta = "tumble.Random";

struct Random {
  std::uint64_t s[4];
  std::uint64_t seed;
};

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

std::uint64_t next(Random& r) {
  std::uint64_t result = rotl(r.s[1] * 5, 7) * 9;
  std::uint64_t t = r.s[1] << 17;
  r.s[2] ^= r.s[0];
  r.s[3] ^= r.s[1];
  r.s[1] ^= r.s[2];
  r.s[0] ^= r.s[3];
  r.s[2] ^= t;
  r.s[3] = rotl(r.s[3], 45);
  return result;
}

double unit(Random& r) { return double(next(r) >> 11) * 0x1.0p-53; }  // [0, 1)

void pushRandom(lua_State* L, std::uint64_t seed) {
  auto* r = static_cast<Random*>(lua_newuserdatauv(L, sizeof(Random), 0));
  std::uint64_t x = seed;
  for (auto& word : r->s) word = splitmix64(x);
  r->seed = seed;
  luaL_setmetatable(L, kRandomMeta);
}

Random& checkRandom(lua_State* L, int idx) {
  auto* r = static_cast<Random*>(luaL_testudata(L, idx, kRandomMeta));
  if (!r) throw LuaArgError(std::string("expected a Random (call it as rng:float(), with a colon), got ") +
                            luaL_typename(L, idx));
  return *r;
}

/// @function random.new
/// A new generator. The same seed gives the same sequence on every run.
/// @param seed? integer any integer (default: derived from the run's --seed, different for each call)
/// @return Random the generator
/// @example local rng = random.new(42)
/// @example local x = rng:float(-5, 5)
int randomNew(lua_State* L) {
  std::uint64_t seed;
  if (lua_isnoneornil(L, 1)) {
    seed = ScenarioHost::from(L)->nextRandomSeed();
  } else {
    int isint = 0;
    lua_Integer v = lua_tointegerx(L, 1, &isint);
    if (!isint) throw LuaArgError(std::string("random.new: the seed must be an integer, got ") + luaL_typename(L, 1));
    seed = std::uint64_t(v);
  }
  pushRandom(L, seed);
  return 1;
}

/// @class Random
/// A random number generator (xoshiro256**) made by random.new.

/// @function Random:float
/// A uniform number: in [0, 1) without arguments, [0, a) with one, [a, b) with two.
/// @param a? number lower bound (or the upper bound when alone)
/// @param b? number upper bound
/// @return number
/// @example local angle = rng:float(0, 2 * math.pi)
int randomFloat(lua_State* L) {
  Random& r = checkRandom(L, 1);
  double u = unit(r);
  if (lua_isnoneornil(L, 2)) {
    lua_pushnumber(L, u);
  } else if (lua_isnoneornil(L, 3)) {
    lua_pushnumber(L, u * checkNumber(L, 2, "Random:float upper bound"));
  } else {
    double a = checkNumber(L, 2, "Random:float lower bound"), b = checkNumber(L, 3, "Random:float upper bound");
    lua_pushnumber(L, a + (b - a) * u);
  }
  return 1;
}

lua_Integer checkInteger(lua_State* L, int idx, const char* what) {
  int isint = 0;
  lua_Integer v = lua_tointegerx(L, idx, &isint);
  if (!isint) throw LuaArgError(std::string(what) + ": expected an integer, got " + luaL_typename(L, idx));
  return v;
}

/// @function Random:int
/// A uniform integer in [a, b], both included (no modulo bias).
/// @param a integer smallest value
/// @param b integer largest value (>= a)
/// @return integer
/// @example local die = rng:int(1, 6)
int randomInt(lua_State* L) {
  Random& r = checkRandom(L, 1);
  lua_Integer a = checkInteger(L, 2, "Random:int a"), b = checkInteger(L, 3, "Random:int b");
  if (b < a) throw LuaArgError("Random:int: b must be >= a, got a = " + std::to_string(a) + ", b = " + std::to_string(b));
  std::uint64_t span = std::uint64_t(b) - std::uint64_t(a);  // values - 1
  std::uint64_t v;
  if (span == ~0ull) {
    v = next(r);
  } else {
    // Rejection: the values at or above 2^64 mod n come in whole runs of n.
    std::uint64_t n = span + 1, threshold = (0 - n) % n;
    do v = next(r); while (v < threshold);
    v %= n;
  }
  lua_pushinteger(L, lua_Integer(std::uint64_t(a) + v));
  return 1;
}

/// @function Random:normal
/// A normally distributed number (Box-Muller).
/// @param mean? number default 0
/// @param sd? number standard deviation >= 0, default 1
/// @return number
/// @example local height = rng:normal(1.75, 0.1)
int randomNormal(lua_State* L) {
  Random& r = checkRandom(L, 1);
  double mean = lua_isnoneornil(L, 2) ? 0.0 : checkNumber(L, 2, "Random:normal mean");
  double sd = lua_isnoneornil(L, 3) ? 1.0 : checkNumber(L, 3, "Random:normal sd");
  if (sd < 0) throw LuaArgError("Random:normal: sd must be >= 0");
  double u1 = 1.0 - unit(r);  // (0, 1]: log is finite
  double u2 = unit(r);
  lua_pushnumber(L, mean + sd * std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2));
  return 1;
}

/// @function Random:chance
/// True with probability p.
/// @param p number probability, 0..1
/// @return boolean
/// @example if rng:chance(0.1) then game.message("a gust of wind!") end
int randomChance(lua_State* L) {
  Random& r = checkRandom(L, 1);
  double p = checkNumber(L, 2, "Random:chance p");
  if (p < 0 || p > 1) throw LuaArgError("Random:chance: p must be a probability in 0..1");
  lua_pushboolean(L, unit(r) < p);
  return 1;
}

/// @function Random:pick
/// A uniformly chosen element of a list.
/// @param list table a non-empty sequence
/// @return any one of its elements
/// @example local colour = rng:pick{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}
int randomPick(lua_State* L) {
  Random& r = checkRandom(L, 1);
  if (!lua_istable(L, 2)) throw LuaArgError(std::string("Random:pick: expected a list, got ") + luaL_typename(L, 2));
  lua_Unsigned n = lua_rawlen(L, 2);
  if (n == 0) throw LuaArgError("Random:pick: the list is empty");
  lua_rawgeti(L, 2, lua_Integer(1 + std::uint64_t(unit(r) * double(n)) % n));
  return 1;
}

/// @function Random:seed
/// @return integer the seed this generator started from
int randomSeed(lua_State* L) {
  lua_pushinteger(L, lua_Integer(checkRandom(L, 1).seed));
  return 1;
}

// random.float(...) == scenarioRandom:float(...): the generator is upvalue 1,
// passed as the method's first argument (F is the guarded method, so its
// stack check counts the generator as an argument).
template <int (*F)(lua_State*)>
int onDefault(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  return F(L);
}

const luaL_Reg kMethods[] = {
    {"float", guarded<randomFloat>},   {"int", guarded<randomInt>},   {"normal", guarded<randomNormal>},
    {"chance", guarded<randomChance>}, {"pick", guarded<randomPick>}, {"seed", guarded<randomSeed>},
    {nullptr, nullptr},
};

}  // namespace

/// @function random.float
/// Random:float on the scenario's generator (seeded from --seed).
/// @param a? number lower bound (or the upper bound when alone)
/// @param b? number upper bound
/// @return number

/// @function random.int
/// Random:int on the scenario's generator (seeded from --seed).
/// @param a integer smallest value
/// @param b integer largest value
/// @return integer

/// @function random.normal
/// Random:normal on the scenario's generator (seeded from --seed).
/// @param mean? number default 0
/// @param sd? number default 1
/// @return number

/// @function random.chance
/// Random:chance on the scenario's generator (seeded from --seed).
/// @param p number probability, 0..1
/// @return boolean

/// @function random.pick
/// Random:pick on the scenario's generator (seeded from --seed).
/// @param list table a non-empty sequence
/// @return any

void openRandomBindings(lua_State* L, int envIndex) {
  registerType(L, {kRandomMeta, kMethods});

  lua_createtable(L, 0, 6);
  lua_pushcfunction(L, guarded<randomNew>);
  rawSetField(L, -2, "new");
  pushRandom(L, ScenarioHost::from(L)->nextRandomSeed());  // the scenario's generator
  const std::pair<const char*, lua_CFunction> shared[] = {
      {"float", onDefault<guarded<randomFloat>>},   {"int", onDefault<guarded<randomInt>>},
      {"normal", onDefault<guarded<randomNormal>>}, {"chance", onDefault<guarded<randomChance>>},
      {"pick", onDefault<guarded<randomPick>>},
  };
  for (const auto& [name, fn] : shared) {
    lua_pushvalue(L, -1);
    lua_pushcclosure(L, fn, 1);
    rawSetField(L, -3, name);
  }
  lua_pop(L, 1);
  rawSetField(L, envIndex, "random");
}

}  // namespace tumble::script
