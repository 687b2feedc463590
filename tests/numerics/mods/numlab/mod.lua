-- Test mod of the numerics lab: bad input to ode, deformable and world.spring
-- gives clear Lua errors (never a crash), and the state survives them.
return {name = "numlab", version = "0.1.0", title = "Numerics lab input checks", api = 1}
