return {name = "sweeptest", version = "1.0.0", title = "Sweep tests' scenarios", api = 1}
