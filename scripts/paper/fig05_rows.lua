-- Figure 5: rows. The same piece with 6, 12 and 18 rows, on three rails side by side: more rows
-- make a longer net; the columns, and so the top spacing, stay.
--
--   build/tools/netsculpt run scripts/paper/fig05_rows.lua --out out/fig05
--
-- Writes knots.csv, report.json, figure.png. GalleryTests checks the pieces' rows (6, 12, 18) and
-- knot counts (24 x rows) in the CSV, and that the lowest knot of each hangs lower with more rows.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
for i, rows in ipairs{6, 12, 18} do
  local x = (i - 2) * 3.0
  local rail = doc:add_rail{name = rows .. " rows", points = {{x - 1.2, 0, 4}, {x + 1.2, 0, 4}}}
  local piece = doc:attach_to_rail{rail = rail, columns = 24, rows = 6, bar = 0.12}
  doc:set_rows{piece = piece, rows = rows} -- rebuilt with its join kept
  doc:rename{piece = piece, name = rows .. " rows"}
end
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750, view = "front"})
