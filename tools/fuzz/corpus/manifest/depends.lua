return {name = "x", version = "1.0", title = "t", api = 1, depends = {"base >= 1.0", "other"}}
