return {name = "x", version = 1}
