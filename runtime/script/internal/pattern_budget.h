#pragma once
// string.find, string.match, string.gmatch and string.gsub under the
// instruction budget: each counts the steps its match takes (PatternCost,
// pattern_cost.h) and charges them to the running call before Lua's own
// function does the match. A match that does not fit in what is left is not
// run: the budget is marked as hit, as a runaway loop's, so the callback
// stops with the budget's message (LuaVm::call) naming the line.
struct lua_State;

namespace tumble::script {

class LuaVm;

/// Replaces the four functions in the state's global `string` table (call
/// before any copy of it is made).
void installPatternBudget(lua_State* L, LuaVm* vm);

}  // namespace tumble::script
