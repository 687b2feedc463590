return {rate = 40, lifetime = {0.5, 1}, color = {{0, 1, 1, 1}, {1, 1, 0, 0}}, size = {0.1, 0.3}, speed = {1, 2}}
