-- Figure 1: two closed rails, read from a CAD file, and a tube between them: hung from the upper
-- rail, its last row tied to the lower one.
--
--   build/tools/netsculpt run scripts/paper/fig01_two_rails.lua --out out/fig01
--
-- data/two_rails.dxf holds the rails as two DXF CIRCLEs (UPPER: r = 1.5 m at z = 5 m, LOWER:
-- r = 2.25 m at z = 2 m; $INSUNITS = metres); bars of 0.28 m make the tube a little longer
-- than the rails are apart (with 0.24 m it was pulled 7 % longer than rope stretches).
-- Writes rails.png (the rails alone), knots.csv,
-- report.json and figure.png. tests/tools/GalleryTests.cpp checks: 2 closed rails, a closed tube
-- of 40 x 16 = 640 knots, the last row (40 knots) held by the lower rail.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local rails = doc:import_rails("data/two_rails.dxf")
assert(#rails == 2, "the DXF holds two rails")
local upper, lower = rails[1], rails[2]
if upper:point(0)[3] < lower:point(0)[3] then upper, lower = lower, upper end -- by height
doc:rename{rail = upper, name = "upper"}
doc:rename{rail = lower, name = "lower"}
doc:export("rails.png", {width = 1000, height = 750})

local tube = doc:attach_to_rail{rail = upper, columns = 40, rows = 16, bar = 0.28}
doc:connect_to_rail{piece = tube, rail = lower, at = 0}
doc:relax{max_seconds = quick and 5 or 60}

doc:export("knots.csv")
doc:write_report("report.json")
doc:export("figure.png", {width = 1000, height = 750})
