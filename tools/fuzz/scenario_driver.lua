-- The scenario fuzzer's driver (fuzz_scenario.cpp): a scenario that reads
-- the fuzz input as a program of Lua API calls with random arguments. The
-- target puts these in front of it:
--   INPUT     the fuzz input (a string)
--   KEYS      every backticked name in docs/lua-api.md (fields, parameters)
--   WORDS     every quoted word in docs/lua-api.md ("hinge", "box", ...)
--   METHODS   every Type:method name in docs/lua-api.md
--   TABLES    the table constructors of docs/lua-api.md's examples (source)
--   EXAMPLES  docs/lua-api.md's example blocks (source)
-- Every call is made inside pcall: the engine may refuse anything with a
-- Lua error, and must not crash, abort, hang or misbehave (ASan, UBSan).
local pos = 0
local function byte()
  pos = pos + 1
  return string.byte(INPUT, pos) or 0
end
local function pick(list)
  if #list == 0 then return nil end
  return list[(byte() * 256 + byte()) % #list + 1]
end

local HUGE = string.rep("x", 300000)
local NUMBERS = {0, -0.0, 1, -1, 2, 0.5, 3, 10, 60, 100, 1e-10, 1e-300, 1e6, 1e10, 1e39, 1e308, -1e308,
  math.huge, -math.huge, 0 / 0, math.maxinteger, math.mininteger, 2 ^ 53, 4096, 65536, -7}
local STRINGS = {"", "\0", "base:buggy", "base", "buggy", "../../../../etc/passwd", "/dev/zero", "a/../b", "%",
  "%d%d%d%d%d%d%d%d%d%d%d%d%d%d%d%d%d%d", "(((((((((((((((((((((((((((((((((", "base:", ":", "x:y:z", HUGE}

local objects = {}  -- what calls returned: bodies, joints, vehicles, emitters, tables
local function remember(v)
  local t = type(v)
  if (t == "userdata" or t == "table") and #objects < 64 then objects[#objects + 1] = v end
end

local value
local function tableOf(depth)
  local t = {}
  for _ = 1, byte() % 6 do
    local k = byte() % 3
    if k == 0 then t[#t + 1] = value(depth + 1)
    elseif k == 1 then t[pick(KEYS) or "x"] = value(depth + 1)
    else t[value(depth + 1) or 1] = value(depth + 1) end
  end
  return t
end
local function docTable(depth)
  local src = pick(TABLES)
  local f = src and load("return " .. src, "=table", "t", _ENV)
  local ok, t = false, nil
  if f then ok, t = pcall(f) end
  if not ok or type(t) ~= "table" then return tableOf(depth) end
  for _ = 1, byte() % 3 do  -- change a few fields
    local ok2 = pcall(function() t[pick(KEYS) or "x"] = value(depth + 1) end)
    if not ok2 then break end
  end
  return t
end
local function hostile(depth)
  -- A table whose metamethods error, lie, or call back into the engine.
  local k = byte() % 6
  local mt = {}
  if k == 0 then mt.__index = function() error("index refused") end
  elseif k == 1 then mt.__index = function(_, key) return value(depth + 1) end
  elseif k == 2 then mt.__index = function() local o = pick(objects); if o then pcall(function() o:remove() end) end return 1 end
  elseif k == 3 then mt.__newindex = function() error("newindex refused") end
  elseif k == 4 then mt.__len = function() return math.maxinteger end
  else mt.__index = function() while true do end end end  -- runs out of the budget
  mt.__tostring = function() error("tostring refused") end
  mt.__eq = function() error("eq refused") end
  return setmetatable(tableOf(depth), mt)
end

value = function(depth)
  depth = depth or 0
  if depth > 4 then return nil end
  local k = byte() % 16
  if k == 0 then return nil
  elseif k <= 2 then return NUMBERS[byte() % #NUMBERS + 1]
  elseif k == 3 then return (byte() - 128) * 2.0 ^ (byte() % 80 - 40)
  elseif k == 4 then return byte() - 16
  elseif k == 5 then return pick(STRINGS)
  elseif k == 6 then return pick(WORDS)
  elseif k == 7 then return byte() % 2 == 0
  elseif k == 8 then return {value(depth + 1), value(depth + 1), value(depth + 1)}
  elseif k == 9 then return {x = value(depth + 1), y = value(depth + 1), z = value(depth + 1)}
  elseif k == 10 then return tableOf(depth)
  elseif k == 11 then return docTable(depth)
  elseif k == 12 then return hostile(depth)
  elseif k == 13 then return pick(objects)
  elseif k == 14 then
    local n = byte() % 3
    return function(...)
      if n == 0 then error("callback refused") elseif n == 1 then return value(depth + 1) end
      local f = pick(FUNCTIONS)
      if f then pcall(f.fn, ...) end
    end
  else
    local n = byte() % 24
    return string.sub(INPUT, pos + 1, pos + n)
  end
end

-- Every function of every module the sandbox offers, in a fixed order.
FUNCTIONS = {}
local names = {}
for name in pairs(_ENV) do if type(name) == "string" then names[#names + 1] = name end end
table.sort(names)
for _, name in ipairs(names) do
  local v = _ENV[name]
  if type(v) == "function" and name ~= "error" then
    FUNCTIONS[#FUNCTIONS + 1] = {name = name, fn = v}
  elseif type(v) == "table" and name ~= "_G" and name ~= "_ENV" then
    local fns = {}
    for fname, f in pairs(v) do if type(f) == "function" then fns[#fns + 1] = fname end end
    table.sort(fns)
    for _, fname in ipairs(fns) do FUNCTIONS[#FUNCTIONS + 1] = {name = name .. "." .. fname, fn = v[fname]} end
  end
end

local function args()
  local a = {}
  local n = byte() % 6
  for i = 1, n do a[i] = value(0) end
  return a, n
end

local function step(budget)
  for _ = 1, budget do
    if pos >= #INPUT then return end
    local k = byte() % 8
    if k <= 4 then
      local f = pick(FUNCTIONS)
      local a, n = args()
      local r = table.pack(pcall(f.fn, table.unpack(a, 1, n)))
      for i = 2, r.n do remember(r[i]) end
    elseif k <= 6 then
      local o, m = pick(objects), pick(METHODS)
      if o and m then
        local ok, f = pcall(function() return o[m] end)
        if ok and type(f) == "function" then
          local a, n = args()
          local self = byte() % 8 == 0 and value(0) or o
          local r = table.pack(pcall(f, self, table.unpack(a, 1, n)))
          for i = 2, r.n do remember(r[i]) end
        end
      end
    else
      local src = pick(EXAMPLES)
      local f = src and load(src, "=example", "t", _ENV)
      if f then pcall(f) end
    end
  end
end

return {
  on_start = function(ctx) remember(ctx); step(48) end,
  on_update = function(ctx, dt) step(4) end,
  on_finish = function(ctx) step(4) end,
}
