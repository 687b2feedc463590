-- The sky only, at night under a storm: the environment API test compares
-- its picture with good:sky.
return {
  duration = 0.1,
  on_start = function()
    environment.set{time_of_day = 1.5, weather = "storm", clouds = 1}
    local e = environment.get()
    expect("time of day kept", e.time_of_day, {min = 1.5, max = 1.5})
    expect("weather kept", e.weather == "storm")
  end,
}
