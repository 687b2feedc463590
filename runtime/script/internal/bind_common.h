#pragma once
#include "physics/world.h"
#include "script/internal/bindings.h"
#include "script/internal/lua_util.h"
#include "script/scenario_host.h"

namespace tumble::script {

constexpr const char* kBodyMeta = "tumble.Body";

/// The body at idx; throws a clear Lua error for a non-body or a removed one.
physics::BodyId checkBody(lua_State* L, int idx);
/// The handle at idx if it is a Body (removed or not); false otherwise.
bool testBody(lua_State* L, int idx, physics::BodyId* out);

}  // namespace tumble::script
