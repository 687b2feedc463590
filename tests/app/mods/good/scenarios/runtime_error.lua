-- on_update indexes a nil value on line 6: a script error, the run goes on.
local n = 0
return {
  duration = 0.5,
  on_update = function(ctx, dt)
    n = n + nothing.field
  end,
  on_finish = function() expect("finished anyway", true) end,
}
