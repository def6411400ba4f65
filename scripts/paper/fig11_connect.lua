-- Figure 11: connecting a last row to a rail. Two equal tubes hang from equal rings; each one's
-- last row is tied to a lower ring, the left one straight below (at = 0), the right one turned
-- by a sixth of the ring against the rail's direction (at = 1/6, reverse), which twists it: its
-- columns cross the axis, so it must reach across the ring as well as down. Both tubes are long
-- enough for that (20 rows of 0.2 m bars for rings 2.2 m apart) and sag below the lower ring;
-- with the 14 rows and 3 m of an earlier version they were stretched by up to 57 %, which the
-- report now flags ("Check the design").
--
--   build/tools/netsculpt run scripts/paper/fig11_connect.lua --out out/fig11
--
-- Writes knots.csv, report.json, figure.png. GalleryTests checks: every tube has its row 0 and its
-- last row fixed (2 x 30 fixed knots each in the CSV), the lower rings carry 30 attachments each.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
for i, twist in ipairs{{at = 0, reverse = false}, {at = 1 / 6, reverse = true}} do
  local x = (i == 1) and -2.0 or 2.0
  local top = doc:add_rail{name = "top " .. i, closed = true,
                           points = ns.circle{radius = 1.0, points = 60, centre = {x, 0, 4.5}}}
  local bottom = doc:add_rail{name = "bottom " .. i, closed = true,
                              points = ns.circle{radius = 1.2, points = 60, centre = {x, 0, 2.3}}}
  local tube = doc:attach_to_rail{rail = top, columns = 30, rows = 20, bar = 0.2}
  doc:connect_to_rail{piece = tube, rail = bottom, at = twist.at, reverse = twist.reverse}
  doc:rename{piece = tube, name = i == 1 and "straight" or "twisted"}
end
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
