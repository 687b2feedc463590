// Snapshots (`run --load-state FILE`, world.restore): the state readers of
// every system on damaged and hand-edited bytes, in a running scene.
//
// A snapshot file's checksum only tells an accident from the file as
// written; anyone can edit a state and write the matching checksum. So the
// readers behind it must refuse, or take, any bytes without a crash, and a
// state they take must step without one. Random bytes would stop at each
// reader's first check (magic, version, counts), so the input here is a
// list of edits to a real state: the scene below (every shape kind, a
// static model, joints of each kind, a spring, a rope and cloth, particles,
// a car, timers, triggers, ctx.state, an ODE system, what is drawn) is run
// for 20 steps and saved once, per system (script::saveSystems) and for
// the scenario's Lua (ScenarioHost::saveState), as `--save-state` saves it.
//
// Each 8-byte record of the input edits one part (world, joints, vehicles,
// ropes and cloth, particles, script): set a byte, write a 32-bit value,
// write a special 64-bit value (NaN, infinities, huge counts, -0), cut the
// part short, insert or delete bytes, at an offset within the part. The
// edited state is restored as `--load-state` restores it
// (script::restoreSystems, then ScenarioHost::restoreState); a refused part
// puts the saved state back (world.restore does the same), which must
// always be taken. A taken state is stepped twice and hashed, then the
// saved state is put back, so every input starts from the same scene.
// With no edits the restored run must give the hash of the run it was
// saved from: a difference aborts (a snapshot that does not reproduce).
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "app/run_report.h"
#include "fuzz_scene.h"
#include "script/presentation.h"
#include "script/systems_state.h"

namespace {

const char* kScenario = R"(
local M = "base:assets/models/"
local links, boxes = {}, {}
local osc
return {
  title = "snapshot fuzz scene",
  joint_solver = "lagrange",
  on_start = function(ctx)
    world.plane{}
    world.add_static_model(M .. "barrier.obj", {position = {0, 0, 6}})
    boxes[1] = world.box{size = {0.5, 0.5, 0.5}, position = {0, 0.3, 0}, mass = 2, color = {0.9, 0.2, 0.1}}
    boxes[2] = world.sphere{radius = 0.3, position = {0, 1.2, 0}}
    boxes[3] = world.capsule{radius = 0.2, length = 0.8, position = {1, 2, 0}}
    boxes[4] = world.cylinder{radius = 0.3, height = 0.6, position = {-1, 1, 0}}
    boxes[5] = world.hull{points = {{0,0,0}, {1,0,0}, {0,0,1}, {1,0,1}, {0,0.6,0}, {0,0.6,1}}, position = {2, 1, 2}}
    boxes[6] = world.compound{children = {{shape = "box", size = {1, 0.2, 0.2}},
      {shape = "sphere", radius = 0.2, position = {0.5, 0, 0}}}, position = {-2, 1.5, 2}}
    local prev = world.box{size = {0.2, 0.2, 0.2}, position = {3, 4, -3}, type = "static"}
    for i = 1, 4 do
      local b = world.box{size = {0.5, 0.1, 0.1}, position = {3 + 0.5 * i, 4, -3}, mass = 1}
      local types = {"hinge", "ball", "cone_twist", "fixed"}
      links[i] = world.joint{type = types[i], a = b, b = prev, anchor = {3 + 0.5 * i - 0.25, 4, -3}, axis = {0, 0, 1}}
      prev = b
    end
    links[1]:set_motor(2, 10)
    world.spring{a = boxes[2], anchor = {0, 3, 0}, stiffness = 40, damping = 1}
    local rope = deformable.rope{from = {-3, 4, -3}, to = {-3, 2, -3}, segments = 6, mass = 0.3}
    rope:pin(1, prev)
    deformable.cloth{origin = {-5, 4, 0}, u = {0, -1, 0}, v = {1, 0, 0}, columns = 4, rows = 3, wind = {0, 0, 4}}
    particles.spawn("base:smoke", {body = boxes[1], offset = {0, 0.3, 0}})
    local car = vehicle.spawn("base:hatchback", {position = {6, 0, 0}})
    car:set_controls{throttle = 0.5, gear = 1}
    trigger.box{center = {0, 1, 0}, size = {2, 2, 2}, on_enter = function(body) ctx.state.entered = true end}
    timer.every(0.05, function() ctx.state.ticks = (ctx.state.ticks or 0) + 1 end)
    ctx.state.data = {1, "two", {three = true}, 4.5}
    ctx.state.osc = 0
    osc = ode.system{state = {1, 0}, method = "verlet", derivative = function(t, y) return {y[2], -4 * y[1]} end}
    boxes[2]:set_model(M .. "rock.obj")
    environment.set{time_of_day = 19, clouds = 0.6}
    hud.set_lap{time = 1.5, best = 2, gate = 1, gates = 3}
    camera.set_mode("follow", {target = boxes[1]})
    game.message("fuzz", 5)
  end,
  on_update = function(ctx, dt)
    osc:step(dt)
    expect("the box is above the ground", boxes[1]:position().y > -1)
    game.add_score(1)
  end,
}
)";

struct Parts {
  tumble::script::SystemsState systems;
  std::string script;
};

std::string* partOf(Parts& p, int k) {
  switch (k) {
    case 0: return &p.systems.world;
    case 1: return &p.systems.joints;
    case 2: return &p.systems.vehicles;
    case 3: return &p.systems.ropesAndCloth;
    case 4: return &p.systems.particles;
    default: return &p.script;
  }
}

// Values a damaged or hostile state holds: counts at their limits,
// non-finite and signed-zero doubles, indices just past an end.
constexpr std::uint64_t kSpecial[] = {
    0,
    1,
    0xffffffffull,
    0x7fffffffull,
    0x80000000ull,
    0xffffffffffffffffull,
    0x8000000000000000ull,  // -0.0
    0x7ff8000000000000ull,  // NaN
    0x7ff0000000000000ull,  // +inf
    0xfff0000000000000ull,  // -inf
    0x7fefffffffffffffull,  // largest double
    0x0000000000000001ull,  // smallest subnormal
    0x7fc000007fc00000ull,  // two float NaNs
    0x7f8000007f800000ull,  // two float infinities
    0x4e6e6b284e6e6b28ull,  // two floats of 1e9
    0x0000000100000000ull,
};

void applyEdit(std::string& part, const std::uint8_t* e) {
  const std::size_t at = (std::size_t(e[2]) | std::size_t(e[3]) << 8 | std::size_t(e[4]) << 16) % (part.size() + 1);
  switch (e[1] % 6) {
    case 0:  // one byte
      if (at < part.size()) part[at] = char(e[5]);
      break;
    case 1: {  // a 32-bit value
      const std::uint32_t v = std::uint32_t(e[5]) | std::uint32_t(e[6]) << 8 | std::uint32_t(e[7]) << 16;
      for (std::size_t i = 0; i < 4 && at + i < part.size(); ++i) part[at + i] = char((v >> (8 * i)) & 0xff);
      break;
    }
    case 2: {  // a special 64-bit value
      const std::uint64_t v = kSpecial[e[5] % std::size(kSpecial)];
      for (std::size_t i = 0; i < 8 && at + i < part.size(); ++i) part[at + i] = char((v >> (8 * i)) & 0xff);
      break;
    }
    case 3:  // cut short
      part.resize(at);
      break;
    case 4:  // insert bytes
      part.insert(at, std::size_t(e[5] % 16) + 1, char(e[6]));
      break;
    default:  // delete bytes
      part.erase(at, std::size_t(e[5] % 16) + 1);
      break;
  }
}

struct Fixture {
  std::unique_ptr<tumble::app::Scene> scene;
  Parts saved;
  double time_s = 0;
  long long step = 0;
  std::string hashAfter;  ///< the state hash 4 steps after the save, in the run saved from
};

constexpr int kStepsBeforeSave = 20, kStepsAfter = 2;

void step(tumble::app::Scene& scene, long long from, int n) {
  tumble::app::RunTimings timings;
  for (long long i = from; i < from + n; ++i)
    tumble::app::stepScene(scene, tumble::app::StepTime{double(i) * scene.dt_s(), i}, timings);
}

/// Restores p; a refusal's message in *why.
bool restore(Fixture& f, const Parts& p, std::string* why = nullptr) {
  const auto& modDirs = f.scene->host().options().modDirs;
  tumble::Status st = tumble::script::restoreSystems(
      *f.scene, p.systems, [&](const std::string& file) { return tumble::script::isFileInMods(file, modDirs); });
  if (st) st = f.scene->host().restoreState(p.script, f.time_s, f.step);
  if (!st && why) *why = st.error();
  return bool(st);
}

Fixture makeFixture() {
  Fixture x;
  x.scene = tumble::fuzz::sceneFor("snapshot_scene", kScenario);
  if (!x.scene) std::abort();
  x.scene->start();
  step(*x.scene, 0, kStepsBeforeSave);
  x.step = kStepsBeforeSave;
  x.time_s = double(kStepsBeforeSave) * x.scene->dt_s();
  auto script = x.scene->host().saveState();
  if (!script) {
    std::fprintf(stderr, "fuzz: the scene cannot be saved: %s\n", script.error().c_str());
    std::abort();
  }
  x.saved = {tumble::script::saveSystems(*x.scene), *script};
  step(*x.scene, x.step, kStepsAfter);
  x.hashAfter = tumble::app::stateHashText(*x.scene);
  if (!restore(x, x.saved)) std::abort();
  return x;
}

Fixture& fixture() {
  static Fixture f = makeFixture();
  return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Fixture& f = fixture();
  Parts edited = f.saved;
  for (std::size_t i = 0; i + 8 <= size; i += 8) applyEdit(*partOf(edited, data[i] % 6), data + i);
  const bool accepted = restore(f, edited);
  if (accepted) {
    step(*f.scene, f.step, kStepsAfter);
    const std::string hash = tumble::app::stateHashText(*f.scene);
    if (size < 8 && hash != f.hashAfter) {
      std::fprintf(stderr, "fuzz: the unedited snapshot gave %s after %d steps, the run it was saved from %s\n",
                   hash.c_str(), kStepsAfter, f.hashAfter.c_str());
      std::abort();
    }
  } else if (size < 8) {
    std::fprintf(stderr, "fuzz: the unedited snapshot was refused\n");
    std::abort();
  }
  // Every input starts from the saved scene; a refused part may have left
  // the parts before it restored, as world.restore puts the state back.
  // After an accepted state the two steps may have ended what a snapshot
  // cannot bring back (a one-shot timer that fired, a trigger removed: their
  // Lua functions are gone; `run --load-state` loads into a scene fresh from
  // on_start, where they all exist), so the scene is then made afresh. After
  // a refused state nothing may have changed, and the saved state must go
  // back into this very scene.
  if (std::string why; !restore(f, f.saved, &why)) {
    if (!accepted) {
      std::fprintf(stderr, "fuzz: a refused state changed the scene; the saved state could not be put back: %s\n",
                   why.c_str());
      std::abort();
    }
    f = makeFixture();
  }
  return 0;
}
