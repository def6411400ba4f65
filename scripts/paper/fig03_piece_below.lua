-- Figure 3: a piece below a piece. With gear 1 the child's top row *is* the parent's last row:
-- the two pieces share those knots, and the child continues the net downwards.
--
--   build/tools/netsculpt run scripts/paper/fig03_piece_below.lua --out out/fig03
--
-- Writes knots.csv, report.json, figure.png. GalleryTests checks: parent 36 x 10, child 36 x 8;
-- the CSV lists 36 * 10 + 36 * 8 knots, and the 36 of the child's row 0 stand at the positions
-- of the parent's row 9 (one knot for both).

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local ring = doc:add_rail{name = "ring", closed = true,
                          points = ns.circle{radius = 1.0, points = 72, centre = {0, 0, 4.0}}}
local parent = doc:attach_to_rail{rail = ring, columns = 36, rows = 10, bar = 0.15}
local child = doc:attach_to_piece{piece = parent, gear = 1, rows = 8, bar = 0.15}
doc:rename{piece = parent, name = "parent"}
doc:rename{piece = child, name = "child"}
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
