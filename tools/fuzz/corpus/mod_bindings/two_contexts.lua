return {
  contexts = {
    game = {priority = 100, actions = {pause = {type = "button", label = "Pause", bindings = {"key:P", "pad:start"}}}},
    vehicle = {priority = 50, enabled = false, actions = {
      steer = {type = "axis", label = "Steer", bindings = {"key:A-", "key:D+", "pad_axis:leftx"}},
      throttle = {type = "axis", label = "Throttle", bindings = {"key:W", "pad_axis:righttrigger"}},
    }},
  },
}
