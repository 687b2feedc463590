#pragma once
// The bindings' entry points (bind_<topic>.cpp), called once per Lua state
// by ScenarioHost::buildEnvironment, each setting its module or functions
// as fields of the environment at envIndex.
#include <cstdint>

#include "core/byte_stream.h"
#include "core/result.h"
#include "physics/body.h"

struct lua_State;

namespace tumble::script {

/// print, expect, param and hud_text (globals.cpp).
void openGlobalBindings(lua_State* L, int envIndex);
/// Registers the `world` table and Body type (bind_world.cpp, bind_body.cpp).
void openWorldBindings(lua_State* L, int envIndex);
void openBodyType(lua_State* L);
void pushBody(lua_State* L, physics::BodyId id);
void pushTrigger(lua_State* L, std::uint32_t id);
/// game, timer, random and trigger tables (bind_game.cpp, bind_timer.cpp,
/// bind_random.cpp, bind_trigger.cpp), each set as a field of the env.
void openGameBindings(lua_State* L, int envIndex);
void openHudBindings(lua_State* L, int envIndex);
void openTimerBindings(lua_State* L, int envIndex);
void openRandomBindings(lua_State* L, int envIndex);
void openTriggerBindings(lua_State* L, int envIndex);
/// spawn_ragdoll and joints_error (bind_ragdoll.cpp), set in the env.
void openRagdollBindings(lua_State* L, int envIndex);
/// The `particles` table and Emitter type (bind_emitter.cpp).
void openEmitterBindings(lua_State* L, int envIndex);
/// The `input` table: actions by name, contexts, injection (bind_input.cpp).
void openInputBindings(lua_State* L, int envIndex);
/// The tune table (bind_tune.cpp).
void openTuneBindings(lua_State* L, int envIndex);
/// vehicle (bind_vehicle.cpp) and save (bind_save.cpp) tables.
void openVehicleBindings(lua_State* L, int envIndex);
void openSaveBindings(lua_State* L, int envIndex);
/// body:set_model and world.add_static_model (bind_model.cpp; after
/// openWorldBindings and openBodyType), and the camera table (bind_camera.cpp).
void openModelBindings(lua_State* L, int envIndex);
void openCameraBindings(lua_State* L, int envIndex);
/// The environment table: sky, sun, fog, clouds, weather (bind_environment.cpp).
void openEnvironmentBindings(lua_State* L, int envIndex);
/// deformable table (bind_deformable.cpp); ode table and draw_line (bind_ode.cpp).
void openDeformableBindings(lua_State* L, int envIndex);
void openOdeBindings(lua_State* L, int envIndex);
/// The ode.system objects' state for snapshots (bind_ode.cpp): made = how
/// many the scenario made so far (ScenarioHost::noteOdeSystem). Each live
/// one's state vector, time, counters and integrator memory, by its number.
/// restoreOdeSystems puts them into the systems on_start made again, and
/// refuses a live saved one this run has not made (made after on_start) or
/// one of another size or method.
void saveOdeSystems(lua_State* L, int made, ByteWriter& w);
/// apply = false: reads and checks only (nothing changes).
Status restoreOdeSystems(lua_State* L, int made, ByteReader& r, bool apply = true);
/// world.spring and world.remove_spring (bind_spring.cpp); after openWorldBindings.
void openSpringBindings(lua_State* L, int envIndex);
/// world.snapshot and world.restore (bind_world_snapshot.cpp); after openWorldBindings.
void openWorldSnapshotBindings(lua_State* L, int envIndex);
/// world.joint, world.grab, ... and the Joint type (bind_joint.cpp); after openWorldBindings.
void openJointBindings(lua_State* L, int envIndex);
/// The sound table and Sound type (bind_sound.cpp).
void openSoundBindings(lua_State* L, int envIndex);

}  // namespace tumble::script
