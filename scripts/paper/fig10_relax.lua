-- Figure 10: relaxation. The initial geometry (Eq. 1 and 2 of the paper: every bar at its rest
-- length, hanging straight down) and the shape under gravity: a tube between two rings.
--
--   build/tools/netsculpt run scripts/paper/fig10_relax.lua --out out/fig10
--
-- Writes before.csv, before.png, before.json (report), after.csv, after.png, after.json.
-- GalleryTests checks: the relaxation converged; after it the rails' reactions add up to the
-- net's weight, and the knots moved.

local ns = require "netsculpt"

local function circle(r, z, n)
  local points = {}
  for i = 0, n - 1 do
    local a = 2 * math.pi * i / n
    points[#points + 1] = {r * math.cos(a), r * math.sin(a), z}
  end
  return points
end

local doc = ns.new()
local top = doc:add_rail{name = "top", points = circle(1.0, 4.0, 64), closed = true}
local bottom = doc:add_rail{name = "bottom", points = circle(1.4, 2.4, 64), closed = true}
local tube = doc:attach_to_rail{rail = top, columns = 24, rows = 6, bar = 0.3}
doc:connect_to_rail{piece = tube, rail = bottom, at = 0}

doc:export("before.csv")
doc:export("before.png", {width = 1000, height = 750})
doc:write_report("before.json")

local result = doc:relax{max_seconds = 30}
print(string.format("relaxation: %s after %d steps, %.2f s, residual %.2g",
                    result.converged and "converged" or result.stop_reason, result.steps, result.seconds,
                    result.residual))

doc:export("after.csv")
doc:export("after.png", {width = 1000, height = 750})
doc:write_report("after.json")
