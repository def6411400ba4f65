-- Figure 4: splitting a tube. A split changes which piece owns which knots, never the net:
-- splitting the closed tube at column 12 gives two open pieces that share the knots of column 12
-- and of column 0 (the tube's seam).
--
--   build/tools/netsculpt run scripts/paper/fig04_split.lua --out out/fig04
--
-- Writes before.csv (the tube) and after.csv (the two parts), report.json, figure.png.
-- GalleryTests checks: one closed 48-column piece before; after, two open pieces of 13 and 37
-- columns (13 + 37 = 48 + 2 shared columns) with the same set of knot positions as before.

local ns = require "netsculpt"

local doc = ns.new()
local ring = doc:add_rail{name = "ring", closed = true,
                          points = ns.circle{radius = 1.5, points = 96, centre = {0, 0, 4.0}}}
local tube = doc:attach_to_rail{rail = ring, columns = 48, rows = 12, bar = 0.2}
doc:export("before.csv")

local left, right = doc:split{piece = tube, column = 12}
doc:rename{piece = left, name = "left part"}
doc:rename{piece = right, name = "right part"}
doc:set_colour{piece = right, colour = {0.15, 0.5, 0.75}}
assert(left == tube, "the first part keeps the tube's id")

doc:export("after.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
