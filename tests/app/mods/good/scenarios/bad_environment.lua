-- A misspelt environment field: a script error that names it.
return {
  duration = 0.1,
  on_start = function()
    environment.set{time_of_day = 12, weathr = "storm"}
  end,
}
