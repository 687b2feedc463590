-- For the play HUD's messages and the script-error console
-- (tests/app/hud_play_test.cpp): one message of each kind at the start, then
-- at 0.5 s a timer that indexes a nil value on line 13: a script error.
return {
  duration = 60,
  on_start = function(ctx)
    world.plane{}
    world.box{position = {0, 1, 0}}
    game.message("welcome", 1)
    game.message("mind the gap", 2, "warning")
    game.message("engine on fire", 2, "error")
    timer.after(0.5, function()
      local broken = nil; broken.part = 1
    end)
  end,
}
