-- Figure 10: relaxation. The initial geometry (Eq. 1 and 2 of the paper: every bar at its rest
-- length, hanging straight down) and the shape under gravity: a tube between two rings.
--
--   build/tools/netsculpt run scripts/paper/fig10_relax.lua --out out/fig10
--
-- Writes before.csv, before.png, before.json (report), after.csv, after.png, after.json.
-- GalleryTests checks: the relaxation converged; after it the rails' reactions add up to the
-- net's weight, the knots moved, and no bar is stretched more than rope can be (with 6 rows the
-- tube fell short of the lower ring and hung with bars stretched 27 %).

local ns = require "netsculpt"

local doc = ns.new()
local top = doc:add_rail{name = "top", closed = true,
                         points = ns.circle{radius = 1.0, points = 64, centre = {0, 0, 4.0}}}
local bottom = doc:add_rail{name = "bottom", closed = true,
                            points = ns.circle{radius = 1.4, points = 64, centre = {0, 0, 2.4}}}
local tube = doc:attach_to_rail{rail = top, columns = 24, rows = 8, bar = 0.3}
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
