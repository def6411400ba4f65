-- Figure 7: gears. Below a 24-column parent, a child's top row takes g times the parent's
-- columns: g = 3, 2, 1, 1/2, 1/3 give 72, 48, 24, 12 and 8 columns. Gear-up adds knots between
-- the shared ones; gear-down skips parent knots.
--
--   build/tools/netsculpt run scripts/paper/fig07_gears.lua --out out/fig07
--
-- Five rings in a row, each with a parent tube and a child through one gear. Writes knots.csv,
-- report.json and figure.png. GalleryTests checks each child's columns = gear x 24 (report and CSV).

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local gears = {3, 2, 1, "1/2", "1/3"}
local bars = {[3] = 0.13, [2] = 0.15, [1] = 0.18, ["1/2"] = 0.3, ["1/3"] = 0.45}
for i, gear in ipairs(gears) do
  local centre = {(i - 3) * 2.6, 0, 4.0}
  local ring = doc:add_rail{name = "gear " .. gear, closed = true,
                            points = ns.circle{radius = 0.8, points = 48, centre = centre}}
  local parent = doc:attach_to_rail{rail = ring, columns = 24, rows = 6, bar = 0.2}
  local child = doc:attach_to_piece{piece = parent, gear = gear, rows = 6, bar = bars[gear]}
  doc:rename{piece = parent, name = "parent " .. i}
  doc:rename{piece = child, name = "gear " .. gear}
end
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1400, height = 700, view = "front"})
