return {
  on_update = function(ctx, dt)
    if ctx.time > 1 then
  end,
}
