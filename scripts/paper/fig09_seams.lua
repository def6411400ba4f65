-- Figure 9: seams. A tube split into three parts has three seams (columns shared by two parts).
-- Each part varies its bar length across its columns, and at every seam the two parts have the
-- same bar length: setting it on one side sets it on the other.
--
--   build/tools/netsculpt run scripts/paper/fig09_seams.lua --out out/fig09
--
-- Writes knots.csv, report.json, figure.png. GalleryTests checks from the report that at each
-- seam the left part's last bar length equals the right part's first, and the values set.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local ring = doc:add_rail{name = "ring", closed = true,
                          points = ns.circle{radius = 1.5, points = 96, centre = {0, 0, 5.0}}}
local tube = doc:attach_to_rail{rail = ring, columns = 60, rows = 14, bar = 0.2}
local a, rest = doc:split{piece = tube, column = 20}
local b, c = doc:split{piece = rest, column = 20}
-- seams: a|b at a's column 20, b|c at b's column 20, c|a at c's last column (the tube's seam)
doc:set_bar_length{piece = a, column = 20, length = 0.3}  -- seam a|b
doc:set_bar_length{piece = b, column = 20, length = 0.15} -- seam b|c
doc:set_bar_length{piece = a, column = 0, length = 0.2}   -- seam c|a
for i, part in ipairs{a, b, c} do doc:rename{piece = part, name = "part " .. string.char(96 + i)} end
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
