return {name = "box", chassis = {mass = 1000, size = {1.8, 0.6, 4}}, wheels = {}}
