return {name = "vtest", version = "1.0.0", title = "Vehicle API tests", api = 1, depends = {"base >= 1.0"}}
