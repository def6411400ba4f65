-- A tiny test library for the binding's Lua tests (they run through `netsculpt run` and through a
-- stock lua5.4 with netsculpt.so on LUA_CPATH). A failed check raises an error naming the line.
local T = {}

-- The folder of the tests (where testlib.lua is), to find test data from any working directory.
T.dir = (debug.getinfo(1, "S").source:match("^@(.*)[/\\]") or ".")
function T.data(name) return T.dir .. "/data/" .. name end

local function where(level)
  local info = debug.getinfo(level + 1, "Sl")
  return info and (info.short_src .. ":" .. info.currentline) or "?"
end

function T.check(condition, message)
  if not condition then error(where(2) .. ": check failed: " .. tostring(message or ""), 0) end
end

function T.eq(actual, expected, message)
  if actual ~= expected then
    error(where(2) .. ": expected " .. tostring(expected) .. ", got " .. tostring(actual) ..
          (message and (" (" .. message .. ")") or ""), 0)
  end
end

function T.near(actual, expected, tolerance, message)
  if type(actual) ~= "number" or math.abs(actual - expected) > tolerance then
    error(where(2) .. ": expected " .. tostring(expected) .. " +- " .. tostring(tolerance) ..
          ", got " .. tostring(actual) .. (message and (" (" .. message .. ")") or ""), 0)
  end
end

-- Calls f and checks that it raises an error whose message contains every plain string given.
function T.raises(f, ...)
  local ok, message = pcall(f)
  if ok then error(where(2) .. ": expected an error, got none", 0) end
  message = tostring(message)
  for _, part in ipairs({...}) do
    if not message:find(part, 1, true) then
      error(where(2) .. ": the error\n  " .. message .. "\ndoes not contain\n  " .. part, 0)
    end
  end
  return message
end

-- A closed polygon of n points: a circle of radius r at height z.
function T.circle(r, z, n)
  local points = {}
  for i = 0, n - 1 do
    local a = 2 * math.pi * i / n
    points[#points + 1] = {r * math.cos(a), r * math.sin(a), z}
  end
  return points
end

local count = 0
function T.case(name, f)
  f()
  count = count + 1
end

function T.done(name)
  print(name .. ": " .. count .. " cases passed")
end

return T
