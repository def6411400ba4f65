-- A net in a surveyor's coordinates: rails given as easting and northing in metres (a projected
-- grid such as UTM) and heights above sea level, as a site drawing has them. The net is computed
-- from an origin near its rails (README "Files in and out"), so it relaxes to the rope's
-- tolerance as it would about (0, 0, 0), and everything written out is in the site's coordinates.
-- A sheet hung from one beam across a square and tied to a second, lower beam 6 m away.
--
--   build/tools/netsculpt run scripts/site.lua --out out/site
--
-- Writes knots.csv, report.json (the rails' loads, each attachment with its easting, northing and
-- height; `netsculpt report --csv attachments` prints them as a table; the rope's least safety
-- factor against its breaking load), report.md (the summary),
-- sculpture.glb and sculpture.png. NETSCULPT_QUICK=1 caps the relaxation.

local ns = require "netsculpt"
local quick = os.getenv("NETSCULPT_QUICK") == "1" or (arg ~= nil and arg[1] == "--quick")

local east, north, ground = 691050.0, 5335980.0, 519.5 -- the square's corner, and its ground
local doc = ns.new()
local upper = doc:add_rail{name = "upper beam",
                           points = {{east, north, ground + 8},
                                     {east + 8, north + 0.5, ground + 8}}}
local lower = doc:add_rail{name = "lower beam",
                           points = {{east, north + 6, ground + 5},
                                     {east + 8, north + 6.5, ground + 5}}}
local sheet = doc:attach_to_rail{rail = upper, columns = 40, rows = 48, bar = 0.2}
doc:connect_to_rail{piece = sheet, rail = lower}
doc:rename{piece = sheet, name = "sheet"}
-- The rope: a 5 mm polyester braid holds about 4.5 kN straight; knotted into the net a bar holds
-- about half that (a knot weakens rope). The report checks every bar's tension against it.
doc:set_material{piece = sheet, breaking_load = 2200}

local result = doc:relax{max_seconds = quick and 3 or 60}
print(string.format("relaxation: %s after %d steps, %.1f s, residual %.2g (%s)",
                    result.converged and "converged" or result.stop_reason, result.steps,
                    result.seconds, result.residual, result.backend))

doc:export("knots.csv")
doc:export("sculpture.glb", {colour_by = "tension"})
doc:export("sculpture.png", {width = 1600, height = 1200})
doc:write_report("report.json")
doc:write_report("report.md")

local lowest = math.huge
for _, row in ipairs(doc:knots(sheet)) do
  for _, knot in ipairs(row) do lowest = math.min(lowest, knot[3]) end
end
print(string.format("%d knots; the lowest %.2f m above the ground, at %.2f m above sea level",
                    doc:report().knots, lowest - ground, lowest))
