-- Every bad call raises a Lua error that carries the script's file:line, names the call and the
-- argument, shows the bad value and what is allowed; the sculpture is then exactly as before.
local T = require "testlib"
local ns = require "netsculpt"

local doc = ns.new()
local ring = doc:add_rail{name = "ring", points = T.circle(2, 5, 48), closed = true}
local p = doc:attach_to_rail{rail = ring, columns = 36, rows = 6, bar = 0.3}
local before = doc:hash()

-- Runs f (which must fail on the line `line`) and checks the message and that nothing changed.
local function fails(line, f, ...)
  local message = T.raises(f, "test_errors.lua:" .. line .. ": ", ...)
  T.eq(doc:hash(), before, "the sculpture changed after: " .. message)
  T.eq(#doc:pieces(), 1)
  T.eq(#doc:rails(), 1)
end
local function here() return debug.getinfo(2, "l").currentline end

T.case("whole numbers", function()
  fails(here(), function() doc:attach_to_rail{rail = ring, columns = 36, rows = -3} end,
        "attach_to_rail: argument 'rows' must be a whole number from 1 to 100000, got -3")
  fails(here(), function() doc:set_rows{piece = p, rows = 2.5} end,
        "set_rows: argument 'rows' must be a whole number", "got 2.5")
  fails(here(), function() doc:set_rows{piece = p, rows = "3"} end, "got \"3\"")
  fails(here(), function() doc:split{piece = p, column = 0} end,
        "split: column must be from 1 to 35 for piece 1", "got 0") -- the piece's own range
  fails(here(), function() doc:split{piece = p, column = 5000000} end,
        "split: column must be from 1 to 35 for piece 1", "got 5000000")
  fails(here(), function() doc:split{piece = p, column = 1.5} end,
        "split: argument 'column' must be a whole number", "got 1.5")
end)

T.case("extra arguments", function()
  fails(here(), function() doc:hash(1) end, "hash: takes no arguments, got 1 (the extra: 1)")
  fails(here(), function() doc:set_rows({piece = p, rows = 3}, 7) end,
        "set_rows: takes at most 1 argument, got 2 (the extra: 7)")
  fails(here(), function() doc:undo(1, "all") end,
        "undo: takes at most 1 argument, got 2 (the extra: \"all\")")
  fails(here(), function() p:info(p) end, "info: takes no arguments, got 1 (the extra: piece")
  fails(here(), function() ns.circle({radius = 1, points = 8}, 2, 3) end,
        "circle: takes at most 1 argument, got 3 (the extra: 2, 3)")
  -- trailing nils are not arguments
  T.eq(doc:piece_info(p, nil).rows, 6)
end)

T.case("numbers and lengths", function()
  fails(here(), function() doc:attach_to_piece{piece = p, rows = 3, bar = -0.2} end,
        "attach_to_piece: argument 'bar' must be a finite number > 0, got -0.2")
  fails(here(), function() doc:connect_to_rail{piece = p, rail = ring, at = 0 / 0} end,
        "connect_to_rail: argument 'at' must be a finite number, got")
  fails(here(), function() doc:set_material{piece = p, compression_ratio = 2} end,
        "set_material: argument 'compression_ratio' must be from 0 to 1, got 2")
  fails(here(), function() doc:set_colour{piece = p, colour = {1, 2, 0}} end,
        "set_colour: argument 'colour'", "from 0 to 1, got 2")
end)

T.case("a breaking load is a number of newtons > 0 or false; a bad one keeps the journal",
       function()
  local function bytes(path)
    local file = assert(io.open(path, "rb"))
    local text = file:read("a")
    file:close()
    return text
  end
  local journal = bytes(doc:save("errors/before.netj"))
  local expected = "set_material: argument 'breaking_load' must be a finite number of newtons > 0 "
                   .. "(a knotted bar's breaking load), or false for none, got "
  fails(here(), function() doc:set_material{piece = p, breaking_load = 0} end, expected .. "0")
  fails(here(), function() doc:set_material{piece = p, breaking_load = -3000} end,
        expected .. "-3000")
  fails(here(), function() doc:set_material{piece = p, breaking_load = 0 / 0} end,
        expected .. "nan")
  fails(here(), function() doc:set_material{piece = p, breaking_load = math.huge} end,
        expected .. "inf")
  fails(here(), function() doc:set_material{piece = p, breaking_load = "3000"} end,
        expected .. "\"3000\"")
  fails(here(), function() doc:set_material{piece = p, breaking_load = true} end,
        expected .. "true")
  fails(here(), function() doc:set_material{piece = p, stiffness = 100, breaking_load = 0} end,
        expected .. "0") -- the other fields are not set either
  T.eq(bytes(doc:save("errors/after.netj")), journal)
end)

T.case("rail positions outside the rail", function()
  fails(here(), function() doc:attach_to_rail{rail = ring, columns = 12, rows = 3, at = 1.5} end,
        "attach_to_rail: rail position 'at' on rail 1 (ring) must be from 0 to 1", "got 1.5")
  fails(here(), function() doc:attach_to_rail{rail = ring, columns = 12, rows = 3, at = -0.1} end,
        "got -0.1")
  fails(here(), function() doc:connect_to_rail{piece = p, rail = ring, at = 1e13} end,
        "connect_to_rail: rail position 'at' on rail 1 (ring) must be from 0 to 1", "got 1e+13")
  fails(here(), function() return ring:point(2) end,
        "point: argument 't' must be a rail position from 0 to 1", "got 2")
  fails(here(), function() return ring:point(-1e300) end, "got -1e+300")
end)

T.case("missing, unknown and misspelt arguments", function()
  fails(here(), function() doc:attach_to_rail{rail = ring, rows = 3} end,
        "attach_to_rail: argument 'columns' (or 'spacing') is missing")
  fails(here(), function() doc:attach_to_rail{rail = ring, colums = 36, rows = 3} end,
        "attach_to_rail: unknown argument \"colums\"; allowed: rail, columns, spacing")
  fails(here(), function() doc:set_rows{rows = 3} end,
        "set_rows: argument 'piece' is missing; expected a piece handle")
  fails(here(), function() doc:set_rows(p, 3) end, "set_rows: expected a table of arguments")
  fails(here(), function() doc.set_rows{piece = p, rows = 3} end, "set_rows: call it as doc:set_rows")
end)

T.case("ns.circle names the bad value", function()
  fails(here(), function() ns.circle{radius = 0, points = 8} end,
        "circle: argument 'radius' must be a finite number > 0, got 0")
  fails(here(), function() ns.circle{radius = 1, points = 2} end,
        "circle: argument 'points' must be a whole number from 3 to 100000, got 2")
  fails(here(), function() ns.circle{radius = 1, points = 8, centre = {0, 0}} end,
        "circle: argument 'centre' must be a point {x, y, z}", "got a table of 2 values")
  fails(here(), function() ns.circle{radius = 1, points = 8, center = {0, 0, 0}} end,
        "circle: unknown argument \"center\"; allowed: radius, points, centre")
  fails(here(), function() ns.circle(1, 8) end,
        "circle: call it as ns.circle{radius, points, centre}, got 1")
end)

T.case("enums list the valid values", function()
  fails(here(), function() doc:add_rail{points = T.circle(1, 1, 8), sampling = "arc"} end,
        "add_rail: argument 'sampling' must be one of \"arclength\" or \"parameter\", got \"arc\"")
  fails(here(), function() doc:attach_to_piece{piece = p, gear = 4, rows = 3} end,
        "attach_to_piece: argument 'gear' must be a gear: 3, 2, 1, 0.5, 1/3", "got 4")
  fails(here(), function() doc:relax{backend = "warp"} end,
        "relax: argument 'backend' must be one of \"auto\"", "got \"warp\"")
  fails(here(), function() doc:relax{tolerance = 2} end,
        "relax: argument 'tolerance' must be a number > 0 and at most 0.01, got 2")
  fails(here(), function() doc:export("x.png", {view = "back"}) end,
        "export: argument 'view' must be one of \"top\", \"side\", \"front\", \"perspective\" or \"all\"")
  fails(here(), function() doc:export("x.docx") end, "export: argument 'path' must end in one of .csv")
  -- An option the format does not use is refused, not ignored.
  fails(here(), function() doc:export("x.csv", {width = 100}) end,
        "export: argument 'width' does not apply to a .csv export (it takes no options)")
  fails(here(), function() doc:export("x.obj", {view = "top"}) end,
        "export: argument 'view' does not apply to a .obj export (it takes tube_radius)")
end)

T.case("handles of the wrong kind or removed", function()
  fails(here(), function() doc:attach_to_rail{rail = p, columns = 36, rows = 3} end,
        "attach_to_rail: argument 'rail' must be a rail handle, got piece 1")
  fails(here(), function() doc:set_rows{piece = 7, rows = 3} end,
        "set_rows: argument 'piece' must be a piece handle, got 7")
end)

T.case("errors from the kernel name the call and keep the sculpture", function()
  fails(here(), function() doc:split{piece = p, column = 40} end, "split: column must be from 1 to 35")
  fails(here(), function() doc:attach_to_piece{piece = p, gear = 1, rows = 3, bar = 0.1} end,
        "attach_to_piece: piece 2: bar length 0.1 m")
  fails(here(), function() doc:remove_rail{rail = ring} end, "remove_rail: cannot remove rail 1 (ring)")
  fails(here(), function() doc:set_gear{piece = p, gear = 2} end, "set_gear: piece 1 hangs from a rail")
  fails(here(), function() doc:redo() end, "redo: nothing to redo")
end)

T.case("a refusal caused by another piece names it, and a row too long for its rail the lengths",
       function()
  local d = ns.new()
  local r = d:add_rail{points = T.circle(2, 5, 24), closed = true}
  local top = d:attach_to_rail{rail = r, columns = 36, rows = 3, bar = 0.4}
  d:attach_to_piece{piece = top, gear = 0.5, rows = 3, bar = 0.8}
  local kept = d:hash()
  T.raises(function() d:set_columns{piece = top, columns = 35} end,
           "set_columns: piece 2, hanging below piece 1: gear 1/2 does not divide a row of 35")
  T.eq(d:hash(), kept)
  local line = d:add_rail{points = {{0, 0, 0}, {3, 0, 0}}}
  local sheet = d:attach_to_rail{rail = line, columns = 7, rows = 3, bar = 0.4}
  kept = d:hash()
  T.raises(function() d:connect_to_rail{piece = sheet, rail = line, at = 0.5} end,
           "piece 3: its last row would run off the end of open rail 2",
           "the row needs 3 m of rail from there, the rail is 3 m long")
  T.eq(d:hash(), kept)
end)

T.done("test_errors")
