-- A storm with nothing else in it: the only sound is the thunder of the
-- lightning the renderer draws (audio_cli_test.cpp). --set weather=clear
-- is the silent control.
return {
  duration = 30,
  params = {weather = {default = "storm", description = "environment.set's weather: storm or clear"}},
  on_start = function()
    environment.set{time_of_day = 15, weather = param("weather")}
  end,
}
