// Lua table `game`: messages, score and the scenario's outcome, stored on the
// ScenarioHost for the HUD and the run report.
#include "script/internal/bind_common.h"

namespace tumble::script {

/// @module game
/// Messages for the player, a score and the outcome (win or lose). The
/// runtime shows them on the HUD and writes them into the run report; the
/// first game.win or game.lose decides, later calls are ignored.

namespace {

std::string textArg(lua_State* L, int idx) { return toDisplayString(L, idx); }

/// @function game.message
/// Shows a message to the player for a while.
/// @param text string the message (other values are converted with tostring)
/// @param seconds? number how long it stays on the HUD, s (default 3); it fades out over its last second
/// @param kind? string "info" (white, the default), "warning" (yellow) or "error" (red)
/// @example game.message("Checkpoint 2 of 5")
/// @example game.message("Fuel low", 5, "warning")
int gameMessage(lua_State* L) {
  if (lua_isnoneornil(L, 1)) throw LuaArgError("game.message: expected the message text");
  double seconds = lua_isnoneornil(L, 2) ? 3.0 : checkNumber(L, 2, "game.message seconds");
  if (seconds <= 0) throw LuaArgError("game.message: seconds must be > 0");
  MessageKind kind = MessageKind::Info;
  if (!lua_isnoneornil(L, 3)) {
    const std::string k = lua_type(L, 3) == LUA_TSTRING ? lua_tostring(L, 3) : "";
    if (k == "info") kind = MessageKind::Info;
    else if (k == "warning") kind = MessageKind::Warning;
    else if (k == "error") kind = MessageKind::Error;
    else
      throw LuaArgError("game.message: kind must be \"info\", \"warning\" or \"error\", got " +
                        (lua_type(L, 3) == LUA_TSTRING ? "\"" + k + "\"" : std::string(luaL_typename(L, 3))));
  }
  ScenarioHost::from(L)->addMessage(textArg(L, 1), seconds, kind);
  return 0;
}

/// @function game.score
/// Sets the score when given a number; returns the score either way.
/// @param n? number the new score
/// @return number the score (0 until one is set)
/// @example game.score(game.score() + 10)
int gameScore(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  if (!lua_isnoneornil(L, 1)) host->setScore(checkNumber(L, 1, "game.score"));
  lua_pushnumber(L, host->score());
  return 1;
}

/// @function game.add_score
/// Adds to the score.
/// @param dn number points to add (may be negative)
/// @return number the new score
/// @example trigger.box{center = {0, 1, 10}, size = {2, 2, 2}, on_enter = function() game.add_score(100) end}
int gameAddScore(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  host->setScore(host->score() + checkNumber(L, 1, "game.add_score"));
  lua_pushnumber(L, host->score());
  return 1;
}

int decide(lua_State* L, Outcome outcome) {
  ScenarioHost* host = ScenarioHost::from(L);
  bool first = host->outcome() == Outcome::None;
  host->decide(outcome, lua_isnoneornil(L, 1) ? std::string() : textArg(L, 1));
  lua_pushboolean(L, first);
  return 1;
}

/// @function game.win
/// The player won. The first win or lose decides the outcome.
/// @param reason? string shown to the player and in the report
/// @return boolean true if this call decided the outcome
/// @example if ball:position().x > 50 then game.win("reached the flag") end
int gameWin(lua_State* L) { return decide(L, Outcome::Won); }

/// @function game.lose
/// The player lost. The first win or lose decides the outcome.
/// @param reason? string shown to the player and in the report
/// @return boolean true if this call decided the outcome
/// @example if ctx.time > 60 then game.lose("out of time") end
int gameLose(lua_State* L) { return decide(L, Outcome::Lost); }

/// @function game.outcome
/// @return string? "won", "lost" or nil while undecided
/// @return string? the reason given to game.win / game.lose
int gameOutcome(lua_State* L) {
  ScenarioHost* host = ScenarioHost::from(L);
  switch (host->outcome()) {
    case Outcome::None: lua_pushnil(L); return 1;
    case Outcome::Won: lua_pushliteral(L, "won"); break;
    case Outcome::Lost: lua_pushliteral(L, "lost"); break;
  }
  lua_pushstring(L, host->outcomeReason().c_str());
  return 2;
}

const luaL_Reg kGame[] = {
    {"message", guarded<gameMessage>},
    {"score", guarded<gameScore>},
    {"add_score", guarded<gameAddScore>},
    {"win", guarded<gameWin>},
    {"lose", guarded<gameLose>},
    {"outcome", guarded<gameOutcome>},
    {nullptr, nullptr},
};

}  // namespace

void openGameBindings(lua_State* L, int envIndex) {
  registerModule(L, envIndex, "game", kGame);
}

}  // namespace tumble::script
