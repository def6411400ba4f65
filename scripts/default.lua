-- The Quick start sculpture (README): a tube hanging from a ring, a wider skirt knotted below it
-- with gear 2 (twice the columns), its last row tied to a larger, lower ring with a small twist.
-- About 2,500 knots.
--
--   build/tools/netsculpt run scripts/default.lua --out out/demo
--
-- Writes into the output folder: knots.csv (every knot), bars.obj (the bars as tubes),
-- sculpture.glb (bars coloured by tension), report.json and report.md (fabrication and loads),
-- sculpture.png (four views), and the session's journal default.netj.
-- NETSCULPT_QUICK=1 (or the argument --quick) relaxes for at most 3 s, as CI does.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local doc = ns.new()
local top = doc:add_rail{name = "top ring", closed = true,
                         points = ns.circle{radius = 1.2, points = 96, centre = {0, 0, 6.0}}}
local bottom = doc:add_rail{name = "lower ring", closed = true,
                            points = ns.circle{radius = 2.2, points = 96, centre = {0, 0, 1.2}}}

local tube = doc:attach_to_rail{rail = top, columns = 48, rows = 20, bar = 0.18}
local skirt = doc:attach_to_piece{piece = tube, gear = 2, rows = 16, bar = 0.15}
doc:connect_to_rail{piece = skirt, rail = bottom, at = 0.03}
doc:rename{piece = tube, name = "tube"}
doc:rename{piece = skirt, name = "skirt"}
doc:set_colour{piece = tube, colour = {0.85, 0.35, 0.20}}
doc:set_colour{piece = skirt, colour = {0.15, 0.50, 0.75}}

local result = doc:relax{max_seconds = quick and 3 or 60}
print(string.format("relaxation: %s after %d steps, %.1f s, residual %.2g (%s)",
                    result.converged and "converged" or result.stop_reason, result.steps,
                    result.seconds, result.residual, result.backend))

doc:export("knots.csv")
doc:export("bars.obj", {tube_radius = 0.004})
doc:export("sculpture.glb", {colour_by = "tension"})
doc:export("sculpture.png", {width = 1600, height = 1200})
doc:write_report("report.json")
doc:write_report("report.md")

local report = doc:report()
print(string.format("%d knots, %.2f kg of net, max tension %.1f N", report.knots,
                    report.total_mass, report.max_tension))
