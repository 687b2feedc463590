-- Default input actions of the base mod. Scripts read them by name
-- (input.value("throttle"), input.pressed("reset")); players rebind them in
-- the bindings menu (F1), which saves only their changes in
-- ~/.config/tumble/bindings.json. Binding texts: see docs/input.md.
--
-- Priority: when two enabled contexts bind the same key, the higher one
-- gets it. "ui" (on only while the pause menu is open) comes first, then
-- "game", so pause, screenshot and the menus always work.
-- "vehicle" and "interact" start off; a scenario switches on what it uses
-- with input.set_context(name, true), so the camera keeps the left mouse
-- button and Space where no scenario asks for them.
return {
  contexts = {
    ui = {
      priority = 200,
      enabled = false,
      actions = {
        ui_up = {type = "button", label = "Menu: up", bindings = {"key:Up", "key:W", "pad:dpup", "pad_axis:lefty-"}},
        ui_down = {type = "button", label = "Menu: down", bindings = {"key:Down", "key:S", "pad:dpdown", "pad_axis:lefty+"}},
        ui_select = {type = "button", label = "Menu: choose", bindings = {"key:Return", "key:Keypad Enter", "key:Space", "pad:a"}},
      },
    },
    game = {
      priority = 100,
      actions = {
        pause_menu = {type = "button", label = "Pause menu (Escape also closes a menu)", bindings = {"key:Escape", "pad:start"}},
        pause = {type = "button", label = "Pause", bindings = {"key:P", "key:Pause"}},
        restart = {type = "button", label = "Restart the scenario", bindings = {"key:F5"}},
        debug_panel = {type = "button", label = "Debug panel (FPS, ms per subsystem)", bindings = {"key:F4"}},
        screenshot = {type = "button", label = "Screenshot", bindings = {"key:F12"}},
        menu = {type = "button", label = "Bindings menu", bindings = {"key:F1", "pad:back"}},
        console = {type = "button", label = "Script-error console (modders)", bindings = {"key:`"}},
        hud = {type = "button", label = "Show or hide the HUD", bindings = {"key:H"}},
      },
    },
    vehicle = {
      priority = 10,
      enabled = false,
      actions = {
        -- Triggers give their travel (0..1), keys give 1.
        throttle = {type = "button", label = "Throttle", bindings = {"key:W", "key:Up", "pad_axis:righttrigger"}},
        brake = {type = "button", label = "Brake", bindings = {"key:S", "key:Down", "pad_axis:lefttrigger"}},
        steer = {
          type = "axis", label = "Steer (left - / right +)",
          bindings = {"keys:A/D", "keys:Left/Right", {"pad_axis:leftx", dead_zone = 0.15, curve = 1.5}},
        },
        handbrake = {type = "button", label = "Handbrake", bindings = {"key:Space", "pad:a"}},
        gear_up = {type = "button", label = "Gear up", bindings = {"key:E", "pad:rightshoulder"}},
        gear_down = {type = "button", label = "Gear down", bindings = {"key:Q", "pad:leftshoulder"}},
        reset = {type = "button", label = "Reset vehicle (upright, where it is)", bindings = {"key:R", "pad:y"}},
        camera = {type = "button", label = "Camera (chase, hood, cockpit, orbit, follow)", bindings = {"key:C", "pad:rightstick"}},
      },
    },
    interact = {
      priority = 5,
      enabled = false,
      actions = {
        -- Hold to drag a rag-doll part or chain link under the pointer (input.pointer()).
        grab = {type = "button", label = "Grab and drag", bindings = {"mouse:left", "pad:rightshoulder"}},
        impulse = {type = "button", label = "Kick (impulse)", bindings = {"key:F", "pad:x"}},
        more_links = {type = "button", label = "More chain links", bindings = {"key:]", "pad:dpup"}},
        fewer_links = {type = "button", label = "Fewer chain links", bindings = {"key:[", "pad:dpdown"}},
        dt_up = {type = "button", label = "Longer time step", bindings = {"key:.", "pad:dpright"}},
        dt_down = {type = "button", label = "Shorter time step", bindings = {"key:,", "pad:dpleft"}},
      },
    },
  },
}
