-- An endless loop in on_start: the instruction budget stops it.
return {
  duration = 0.2,
  on_start = function()
    while true do end
  end,
  on_finish = function() expect("the game went on", true) end,
}
