-- A broken test mod: `tumble check` must list every problem at once.
return {name = "broken", version = "one", api = 1}
