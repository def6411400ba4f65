-- Figure 6: columns. The same ring carries a tube of 24, 36 or 60 columns: more columns mean more,
-- closer knots along the rail (set_columns on a rail respaces the top row over the same rail).
--
--   build/tools/netsculpt run scripts/paper/fig06_columns.lua --out out/fig06
--
-- Writes knots_24.csv, knots_36.csv, knots_60.csv (one tube each), report.json (the last) and
-- figure.png. GalleryTests checks the column counts from the CSVs (every row has that many knots)
-- and that the top row's spacing is the ring's length over the columns.

local ns = require "netsculpt"

local doc = ns.new()
local ring = doc:add_rail{name = "ring", closed = true,
                          points = ns.circle{radius = 1.2, points = 120, centre = {0, 0, 4.0}}}
local tube = doc:attach_to_rail{rail = ring, columns = 24, rows = 10, bar = 0.3}
for _, columns in ipairs{24, 36, 60} do
  doc:set_columns{piece = tube, columns = columns}
  assert(tube:info().columns == columns)
  doc:export("knots_" .. columns .. ".csv")
end
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
