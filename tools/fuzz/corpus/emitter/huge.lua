return {rate = 1e400}
