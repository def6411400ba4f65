-- Figure 8: bar length. Two sheets on equal straight rails: the left one has one bar length
-- (0.2 m) everywhere; the right one varies its bar length by row, from 0.12 m at the top row to
-- 0.32 m at the last row (linear in between), so it opens up towards the bottom.
--
--   build/tools/netsculpt run scripts/paper/fig08_bar_length.lua --out out/fig08
--
-- Writes knots.csv, report.json, figure.png. GalleryTests checks the report's bar lengths:
-- constant 0.2 on the left; 0.12 at row 0, 0.32 at row 11 and linear between on the right.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local left_rail = doc:add_rail{name = "left", points = {{-3.5, 0, 4}, {-0.5, 0, 4}}}
local right_rail = doc:add_rail{name = "right", points = {{0.5, 0, 4}, {3.5, 0, 4}}}
local constant = doc:attach_to_rail{rail = left_rail, columns = 21, rows = 12, bar = 0.2}
local graded = doc:attach_to_rail{rail = right_rail, columns = 21, rows = 12, bar = 0.2}
doc:rename{piece = constant, name = "constant"}
doc:rename{piece = graded, name = "graded by row"}
doc:set_bar_length{piece = graded, row = 0, length = 0.12}
doc:set_bar_length{piece = graded, row = 11, length = 0.32}
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750, view = "front"})
