-- A valid test mod: scenarios the app tests drive through `tumble run`.
return {name = "good", version = "0.1.0", title = "App test scenarios", api = 1}
