-- The binding's public API, end to end (DESIGN.md "Lua API"). Runs through `netsculpt run` and
-- through a stock lua5.4 with netsculpt.so on LUA_CPATH; writes into the output folder.
local T = require "testlib"
local ns = require "netsculpt"

T.case("module", function()
  T.eq(type(ns.version), "string")
  T.eq(ns.backends()[1], "auto")
  local formats = table.concat(ns.export_formats(), " ")
  T.check(formats:find("csv") and formats:find("png") and formats:find("dxf"), formats)
end)

T.case("rails: polyline, B-spline, queries", function()
  local doc = ns.new()
  local ring = doc:add_rail{name = "ring", points = T.circle(2, 5, 64), closed = true}
  local info = ring:info()
  T.eq(tostring(ring), "rail 1")
  T.eq(ring.id, 1)
  T.eq(info.name, "ring")
  T.eq(info.closed, true)
  T.eq(info.kind, "polyline")
  T.near(info.length, 64 * 2 * 2 * math.sin(math.pi / 64), 1e-9)
  local p0 = ring:point(0)
  T.near(p0[1], 2, 1e-12); T.near(p0[3], 5, 1e-12)
  local spline = doc:add_rail{name = "arc", degree = 3, closed = false, sampling = "parameter",
                              control = {{0, 0, 4}, {1, 0, 4.5}, {2, 0, 4.5}, {3, 0, 4}}}
  T.eq(spline:info().kind, "bspline")
  T.eq(spline:info().degree, 3)
  T.eq(spline:info().sampling, "parameter")
  T.eq(#doc:rails(), 2)
  T.check(doc:rails()[2] == spline)
  doc:rename{rail = spline, name = "bow"}
  T.eq(doc:rail_info(spline).name, "bow")
  doc:remove_rail{rail = spline}
  T.eq(#doc:rails(), 1)
  T.raises(function() return spline:info() end, "info: rail 2 was removed")
end)

T.case("ns.circle: a ring rail's points", function()
  local ring = ns.circle{radius = 2, points = 64, centre = {0, 0, 5}}
  local reference = T.circle(2, 5, 64)
  T.eq(#ring, 64)
  for i = 1, 64 do
    for k = 1, 3 do T.eq(ring[i][k], reference[i][k], "corner " .. i) end
  end
  local square = ns.circle{radius = 2, points = 4, centre = {1, -3, 6}}
  local expected = {{3, -3}, {1, -1}, {-1, -3}, {1, -5}}
  for i = 1, 4 do
    T.near(square[i][1], expected[i][1], 1e-15); T.near(square[i][2], expected[i][2], 1e-15)
    T.eq(square[i][3], 6)
  end
  T.eq(ns.circle{radius = 1, points = 3}[1][3], 0)
  local doc = ns.new()
  local rail = doc:add_rail{name = "ring", points = ns.circle{radius = 2, points = 64}, closed = true}
  T.near(rail:info().length, 64 * 2 * 2 * math.sin(math.pi / 64), 1e-9)
end)

T.case("site coordinates: knots where the rails are, relaxed to the rope's tolerance", function()
  -- An easting and northing in metres, as a surveyor's drawing has them.
  local site = {512345.678, 5412345.678, 231.5}
  local doc = ns.new()
  local ring = doc:add_rail{points = ns.circle{radius = 1, points = 12, centre = site},
                            closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 12, rows = 8, bar = 0.3}
  local r = doc:relax{}
  T.eq(r.converged, true, r.stop_reason .. ", residual " .. r.residual)
  T.check(r.residual < 1e-6)
  local knots = doc:knots(p)
  local held = ring:point(0) -- column 0 of row 0
  for k = 1, 3 do T.near(knots[1][1][k], held[k], 1e-9) end
  T.check(knots[8][1][3] < site[3] - 1.5, "the net hangs below the ring, at the site's heights")
  T.near(knots[8][1][1], site[1], 1.5)
  T.near(knots[8][1][2], site[2], 1.5)
end)

T.case("import_rails from CSV", function()
  local doc = ns.new()
  local rails = doc:import_rails(T.data("two_rails.csv"))
  T.eq(#rails, 2)
  T.eq(rails[1]:info().name, "upper")
  T.eq(rails[1]:info().closed, true)
  T.near(rails[2]:info().length, 12, 1e-12)
  T.raises(function() doc:import_rails(T.data("none.csv")) end, "import_rails:", "none.csv")
end)

T.case("import_rails: layers chooses the DXF layers to read", function()
  local doc = ns.new()
  local file = T.data("frozen_layer.dxf") -- LINE 3 m long on R, LINE 4 m long on frozen H
  local drawn = doc:import_rails(file, {units = "m"})
  T.eq(#drawn, 1)
  T.eq(drawn[1]:info().name, "R:#1")
  local chosen = doc:import_rails(file, {units = "m", layers = {"h"}})
  T.eq(#chosen, 1)
  T.eq(chosen[1]:info().name, "H:#2")
  T.near(chosen[1]:info().length, 4, 1e-15)
  T.raises(function() doc:import_rails(file, {units = "m", layers = {"X"}}) end,
           "the layer 'X'", "its layers are H, R")
  T.raises(function() doc:import_rails(file, {units = "m", layers = {}}) end,
           "layers", "non-empty list of strings")
  T.raises(function() doc:import_rails(file, {units = "m", layers = "R"}) end, "layers")
end)

T.case("pieces: attach, gears, split, seams, sizes", function()
  local doc = ns.new()
  local ring = doc:add_rail{name = "ring", points = T.circle(2, 5, 64), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 48, rows = 10, bar = 0.25}
  local info = p:info()
  T.eq(tostring(p), "piece 1")
  T.eq(info.rows, 10); T.eq(info.columns, 48); T.eq(info.closed, true); T.eq(info.knots, 480)
  T.check(info.top.rail == ring)
  T.eq(#info.bar_lengths, 48)
  T.eq(info.bar_lengths[1], 0.25)
  for gear, columns in pairs{[2] = 96, ["1/2"] = 24, [0.5] = 24, [1 / 3] = 16, ["x3"] = 144, [1] = 48} do
    local q = doc:attach_to_piece{piece = p, gear = gear, rows = 4, bar = 0.5}
    T.eq(q:info().columns, columns, "gear " .. tostring(gear))
    doc:remove_piece{piece = q}
  end
  local q = doc:attach_to_piece{piece = p, gear = 2, rows = 6, bar = 0.5}
  T.eq(q:info().top.gear, "2")
  T.check(q:info().top.pieces[1] == p)
  doc:set_gear{piece = q, gear = "1/3"}
  T.eq(q:info().columns, 16)
  doc:set_columns{piece = q, columns = 25}
  T.eq(q:info().columns, 24) -- the nearest allowed gear
  doc:set_rows{piece = p, rows = 12}
  T.eq(p:info().rows, 12)
  T.eq(q:info().columns, 24) -- rebuilt below, keeping its join
  local a, b = doc:split{piece = p, column = 12}
  T.check(a == p, "the first part keeps the piece's id")
  T.eq(a:info().columns + b:info().columns, 48 + 2) -- two seams share a column each
  T.check(a:info().right == b and b:info().right == a)
  doc:set_bar_length{piece = a, column = 12, length = 0.3}
  T.eq(a:info().bar_lengths[13], 0.3)
  T.eq(b:info().bar_lengths[1], 0.3) -- equal at the seam
  T.eq(#doc:pieces(), 3)
  local knots = doc:knots(q)
  T.eq(#knots, 6); T.eq(#knots[1], 24); T.eq(#knots[1][1], 3)
end)

T.case("handles: identity, keys, liveness, other documents", function()
  local doc = ns.new()
  local ring = doc:add_rail{points = T.circle(1, 3, 16), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 12, rows = 3, bar = 0.4}
  T.check(rawequal(doc:pieces()[1], p), "the same id gives the same handle")
  local colour = {[p] = "red"}
  T.eq(colour[doc:pieces()[1]], "red")
  T.eq(p.id, 1)
  local other = ns.new()
  local foreign = other:add_rail{points = T.circle(1, 3, 16), closed = true}
  T.check(foreign == ring, "handles compare equal by id")
  T.raises(function() doc:attach_to_rail{rail = foreign, columns = 12, rows = 3} end,
           "attach_to_rail: argument 'rail' is rail 1 of another sculpture")
  doc:remove_piece{piece = p}
  T.raises(function() doc:set_rows{piece = p, rows = 4} end, "set_rows: argument 'piece': piece 1 was removed")
  doc:undo()
  T.eq(p:info().rows, 3) -- alive again
end)

T.case("a handle to an undone piece stays dead when another piece gets its id", function()
  local doc = ns.new()
  local ring = doc:add_rail{points = T.circle(1, 3, 16), closed = true}
  local beam = doc:add_rail{points = {{0, 0, 3}, {3, 0, 3}}}
  local tube = doc:attach_to_rail{rail = ring, columns = 12, rows = 6, bar = 0.3}
  doc:undo()
  T.raises(function() tube:info() end,
           "info: piece 1 no longer exists (the call that made it was undone")
  local sheet = doc:attach_to_rail{rail = beam, columns = 11, rows = 4, bar = 0.3}
  T.eq(sheet.id, tube.id) -- the id is given again ...
  T.check(sheet ~= tube, "... to another piece")
  T.raises(function() doc:set_rows{piece = tube, rows = 20} end,
           "set_rows: argument 'piece': piece 1 no longer exists")
  T.eq(sheet:info().rows, 4) -- the sheet is untouched
  -- undo and redo bring back the same piece: its old handles work again
  doc:undo()
  doc:redo()
  T.eq(sheet:info().rows, 4)
  T.check(rawequal(doc:pieces()[1], sheet))
  -- a split keeps the piece's id for its first part: the handle still names it
  local a, b = doc:split{piece = sheet, column = 5}
  T.check(rawequal(a, sheet))
  T.eq(sheet:info().columns, 6)
  doc:undo()
  T.raises(function() b:info() end, "no longer exists")
  local a2, b2 = doc:split{piece = sheet, column = 3}
  T.eq(b2.id, b.id)
  T.check(b2 ~= b)
  T.raises(function() b:info() end, "no longer exists")
  T.eq(b2:info().columns, 11 - 3)
end)

T.case("edits: material, colour, rename, connect, gravity", function()
  local doc = ns.new()
  local top = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local bottom = doc:add_rail{points = T.circle(1.5, 3, 48), closed = true}
  local p = doc:attach_to_rail{rail = top, columns = 36, rows = 8, bar = 0.3}
  doc:set_material{piece = p, stiffness = 500, knot_mass = 0.004}
  local m = p:info().material
  T.eq(m.stiffness, 500); T.eq(m.knot_mass, 0.004); T.eq(m.compression_ratio, 0.01) -- kept
  T.eq(m.breaking_load, nil) -- none unless given: there is no default strength
  doc:set_material{piece = p, breaking_load = 2500}
  T.eq(p:info().material.breaking_load, 2500); T.eq(p:info().material.stiffness, 500)
  doc:set_material{piece = p, knot_mass = 0.003}
  T.eq(p:info().material.breaking_load, 2500) -- kept by a call that does not name it
  doc:set_material{piece = p, breaking_load = false}
  T.eq(p:info().material.breaking_load, nil)
  doc:undo()
  T.eq(p:info().material.breaking_load, 2500)
  doc:set_colour{piece = p, colour = {0.1, 0.2, 0.3}}
  T.eq(p:info().colour[3], 0.3)
  doc:rename{piece = p, name = "tube"}
  T.eq(p:info().name, "tube")
  doc:connect_to_rail{piece = p, rail = bottom, at = 0.25}
  T.check(p:info().bottom.rail == bottom)
  T.near(p:info().bottom.at, 0.25, 1e-15)
  doc:disconnect{piece = p}
  T.eq(p:info().bottom, nil)
  doc:set_gravity{0, 0, -9.8}
  T.raises(function() doc:set_gravity{0, 0, 0} end, "set_gravity:", "gravity")
end)

T.case("attach_to_piece: the child is knotted from its parent's rope unless told", function()
  local doc = ns.new()
  local top = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local p = doc:attach_to_rail{rail = top, columns = 36, rows = 4, bar = 0.3}
  doc:set_material{piece = p, stiffness = 5e4, compression_ratio = 0.02, knot_mass = 0.011,
                   linear_density = 0.045, breaking_load = 1800}
  local q = doc:attach_to_piece{piece = p, gear = 2, rows = 3, bar = 0.3}
  local m = q:info().material
  T.eq(m.stiffness, 5e4); T.eq(m.compression_ratio, 0.02); T.eq(m.knot_mass, 0.011)
  T.eq(m.linear_density, 0.045); T.eq(m.breaking_load, 1800)
  -- the fields a material table gives replace the parent's; false takes the breaking load away
  local r = doc:attach_to_piece{piece = q, rows = 2, bar = 0.3,
                                material = {stiffness = 7e4, breaking_load = false}}
  m = r:info().material
  T.eq(m.stiffness, 7e4); T.eq(m.knot_mass, 0.011); T.eq(m.breaking_load, nil)
  -- the report checks the child's strength against the rope it inherited
  local rep = doc:report()
  T.eq(rep.pieces[2].breaking_load, 1800)
  T.eq(#rep.pieces_without_breaking_load, 1); T.eq(rep.pieces_without_breaking_load[1], r.id)
  -- a bad material names itself, and the sculpture is as it was
  local h = doc:hash()
  T.raises(function()
    doc:attach_to_piece{piece = r, rows = 2, bar = 0.3, material = {stiffness = -1}}
  end, "attach_to_piece: material: argument 'stiffness'", "got -1")
  T.raises(function()
    doc:attach_to_piece{piece = r, rows = 2, bar = 0.3, material = {stifness = 1}}
  end, "attach_to_piece: material: unknown argument \"stifness\"")
  T.raises(function()
    doc:attach_to_piece{piece = r, rows = 2, bar = 0.3, material = 5}
  end, "argument 'material' must be a table", "got 5")
  T.raises(function()
    doc:attach_to_piece{piece = r, rows = 2, bar = 0.3, material = {knot_mass = 0, linear_density = 0}}
  end, "must weigh something")
  T.eq(doc:hash(), h)
end)

T.case("undo, redo, hash", function()
  local doc = ns.new()
  local h0 = doc:hash()
  local ring = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 5, bar = 0.4}
  local h2 = doc:hash()
  doc:set_rows{piece = p, rows = 7}
  T.check(doc:hash() ~= h2)
  doc:undo()
  T.eq(doc:hash(), h2)
  doc:redo()
  T.eq(p:info().rows, 7)
  doc:undo(); doc:undo(); doc:undo()
  T.eq(doc:hash(), h0)
  T.eq(doc:can_undo(), false)
  T.raises(function() doc:undo() end, "undo: nothing to undo")
end)

T.case("undo and redo several steps at once", function()
  local doc = ns.new()
  local ring = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 5, bar = 0.4}
  local h2 = doc:hash()
  doc:set_rows{piece = p, rows = 7}
  doc:set_columns{piece = p, columns = 48}
  local h4 = doc:hash()
  doc:undo(2)
  T.eq(doc:hash(), h2)
  T.eq(p:info().rows, 5)
  doc:redo(2)
  T.eq(doc:hash(), h4)
  T.eq(p:info().columns, 48)
  -- more steps than there are: refused whole, nothing undone
  T.raises(function() doc:undo(5) end, "undo: argument 'steps' must be at most 4", "got 5")
  T.eq(doc:hash(), h4)
  doc:undo(4)
  T.eq(doc:can_undo(), false)
  T.raises(function() doc:redo(0) end, "redo: argument 'steps' must be a whole number", "got 0")
  T.raises(function() doc:redo(5) end, "redo: argument 'steps' must be at most 4", "got 5")
  T.eq(#doc:rails(), 0)
  doc:redo(nil)
  T.eq(#doc:rails(), 1)
end)

T.case("rails alone: doc:export(path, {rails = true}) reads back with import_rails", function()
  local doc = ns.new()
  doc:add_rail{name = "top ring", points = T.circle(2, 5, 12), closed = true}
  doc:add_rail{name = "edge, east", points = {{0.1, 0, 1}, {1, 0, 1}, {1, 1 / 3, 1.5}}}
  T.eq(table.concat(ns.rail_export_formats(), " "), "csv obj dxf")
  for _, ext in ipairs{"csv", "obj", "dxf"} do
    local path = doc:export("api/rails." .. ext, {rails = true})
    local rails = ns.new():import_rails(path)
    T.eq(#rails, 2, ext)
    for i, rail in ipairs(rails) do
      local before, after = doc:rails()[i]:info(), rail:info()
      T.eq(after.name, before.name, ext)
      T.eq(after.closed, before.closed, ext)
      T.eq(after.points, before.points, ext)
      T.eq(after.length, before.length, ext) -- every bit: the same points
      for _, t in ipairs{0, 0.37, 0.5, 0.999} do
        local a, b = rail:point(t), doc:rails()[i]:point(t)
        for axis = 1, 3 do T.eq(a[axis], b[axis], ext) end
      end
    end
  end
  -- the rails export takes no other option, and only its own formats
  T.raises(function() doc:export("api/rails.dxf", {rails = true, tube_radius = 0.01}) end,
           "export: argument 'tube_radius' does not apply to a rails export (it takes no options)")
  T.raises(function() doc:export("api/rails.png", {rails = true}) end,
           "export: argument 'path' of a rails export must end in one of .csv, .obj, .dxf",
           "got \"api/rails.png\"")
  T.raises(function() doc:export("api/net.dxf", {width = 300}) end,
           "export: argument 'width' does not apply to a .dxf export (it takes no options)")
  T.raises(function() doc:export("api/rails.csv", {rails = "yes"}) end,
           "export: argument 'rails' must be true or false")
end)

T.case("relax, export, report, save and open", function()
  local doc = ns.new()
  T.eq(doc:last_relax(), nil)
  local ring = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 4, bar = 0.4}
  doc:set_material{piece = p, stiffness = 100}
  local early = doc:relax{max_steps = 2, backend = "rk4"}
  T.eq(early.converged, false); T.eq(early.stop_reason, "step limit")
  -- where the net has not settled: a knot of the piece below the rail (row 0 is held)
  T.eq(early.unsettled_at.piece, p)
  T.check(early.unsettled_at.row >= 1 and early.unsettled_at.row <= 3)
  T.check(early.unsettled_at.column >= 0 and early.unsettled_at.column < 24)
  local r = doc:relax{tolerance = 1e-3, max_seconds = 10, backend = "rk4"}
  T.eq(r.converged, true); T.eq(r.stop_reason, "converged"); T.eq(r.backend, "rk4")
  T.eq(r.unsettled_at, nil)
  T.check(r.steps > 0 and r.evaluations >= r.steps and r.residual < 1e-3)
  T.eq(doc:last_relax().steps, r.steps)
  local knots = doc:knots(p)
  T.check(knots[4][1][3] < knots[1][1][3], "the net hangs below the rail")
  local csv = doc:export("api/knots.csv")
  local lines = 0
  for _ in io.lines(csv) do lines = lines + 1 end
  T.eq(lines, 1 + 96)
  -- the net as DXF: a LINE per bar (24 columns x 3 rows below the ring, two bars up each)
  local dxf, bars = doc:export("api/net.dxf"), 0
  for line in io.lines(dxf) do if line == "LINE" then bars = bars + 1 end end
  T.eq(bars, 24 * 3 * 2)
  T.eq(#ns.new():import_rails(dxf), 1) -- the bars are not read as rails
  local report = doc:report()
  T.eq(#report.pieces, 1); T.eq(report.pieces[1].knots, 96)
  T.near(report.total_weight, report.total_mass * 9.81, 1e-9)
  -- the attachment points' table: one line per point held by the ring, its reactions summing
  -- to the ring's
  local points = doc:write_report("api/points.csv", {table = "attachments"})
  local rows, fz = 0, 0
  for line in io.lines(points) do
    rows = rows + 1
    if rows == 1 then
      T.eq(line, "rail,piece,row,column,t,x,y,z,fx,fy,fz,magnitude,along,load_case")
    else
      local fields = {}
      for field in line:gmatch("[^,]+") do fields[#fields + 1] = tonumber(field) end
      fz = fz + fields[11]
    end
  end
  T.eq(rows, 1 + 24)
  T.near(fz, report.rails[1].reaction.z, 1e-9)
  local reaction = report.rails[1].reaction -- a vector by name and by index
  T.eq(#reaction, 3)
  T.eq(reaction[1], reaction.x)
  T.eq(reaction[3], reaction.z)
  T.raises(function() doc:write_report("api/r.md", {table = "attachments"}) end,
           "write_report: argument 'table' is for a .csv report")
  T.raises(function() doc:write_report("api/r.csv", {table = "bars"}) end,
           "write_report: argument 'table' must be", "\"pieces\" or \"attachments\", got \"bars\"")
  local path = doc:save("api/design.netj")
  local copy = ns.open(path)
  T.eq(copy:hash(), doc:hash())
  doc:save_snapshot("api/design.nets")
  local snap = ns.open(ns.output_dir() .. "/api/design.nets")
  T.eq(snap:knots(snap:pieces()[1])[4][1][3], knots[4][1][3]) -- the relaxed shape, bit for bit
  -- A relative name the script saved opens too: a read not found in the script's folder is
  -- looked for in the output folder (DESIGN's save-then-open).
  T.eq(ns.open("api/design.nets"):hash(), snap:hash())
  -- Each file is named by its kind: a journal under .nets would open without the shape it names.
  T.raises(function() doc:save("api/design.nets") end,
           "save: argument 'path' must end in .netj (a journal; doc:save_snapshot writes a .nets",
           "got \"api/design.nets\"")
  T.raises(function() doc:save_snapshot("api/shape.txt") end,
           "save_snapshot: argument 'path' must end in .nets", "got \"api/shape.txt\"")
  T.raises(function() doc:save("api/x.netj\0y") end, "save: the file name", "holds a NUL")
  T.raises(function() doc:export("api/x.csv\0y") end, "export: the file name", "holds a NUL")
  T.raises(function() doc:write_report("api/x.md\0y") end, "write_report: the file name",
           "holds a NUL")
  T.eq(io.open(ns.output_dir() .. "/api/shape.txt"), nil)
  T.eq(doc:save("api/DESIGN.NETJ"):sub(-11), "DESIGN.NETJ")
end)

T.case("the report checks each piece's largest tension against its breaking load", function()
  local doc = ns.new()
  local ring = doc:add_rail{points = T.circle(2, 5, 48), closed = true}
  local p = doc:attach_to_rail{rail = ring, columns = 24, rows = 4, bar = 0.4}
  local q = doc:attach_to_piece{piece = p, gear = 2, rows = 3, bar = 0.3}
  T.eq(doc:relax{max_seconds = 10}.converged, true)
  local none = doc:report()
  T.eq(none.min_safety_factor, nil); T.eq(none.min_safety_factor_at, nil)
  T.eq(#none.pieces_without_breaking_load, 2)
  T.eq(none.pieces[1].breaking_load, nil)
  T.eq(none.pieces[1].utilisation, nil); T.eq(none.pieces[1].safety_factor, nil)

  doc:set_material{piece = p, breaking_load = 40}
  local r = doc:report()
  local top = r.pieces[1]
  T.eq(top.id, p.id); T.eq(top.breaking_load, 40); T.eq(top.material.breaking_load, 40)
  T.check(top.max_tension > 0, "the tube carries the skirt")
  T.eq(top.utilisation, top.max_tension / 40)
  T.eq(top.safety_factor, 40 / top.max_tension)
  T.eq(top.max_tension_at.piece, p.id)
  T.eq(r.min_safety_factor, top.safety_factor)
  T.eq(r.min_safety_factor_at.piece, p.id)
  T.eq(#r.pieces_without_breaking_load, 1); T.eq(r.pieces_without_breaking_load[1], q.id)
  T.eq(r.pieces[2].safety_factor, nil) -- the skirt is not checked
  local md = io.open(doc:write_report("api/strength.md")):read("a")
  T.check(md:find("| pieces without a breaking load | 2 (piece 2): not checked |", 1, true), md)
end)

T.case("the script's folder is the folder of the script, under netsculpt run and stock lua5.4",
       function()
  T.eq(ns.script_dir(), arg[0]:match("^(.*)/[^/]*$"))
end)

T.case("relax with wind and without continuation", function()
  local doc = ns.new()
  local rail = doc:add_rail{points = {{-1, 0, 3}, {1, 0, 3}}}
  local p = doc:attach_to_rail{rail = rail, columns = 11, rows = 6, bar = 0.15}
  local calm = doc:relax{max_seconds = 10}
  T.eq(calm.converged, true)
  local still = doc:knots(p)[6][6]
  local windy = doc:relax{max_seconds = 10, continuation = false, wind = {direction = {0, 1, 0}, pressure = 0.05}}
  T.eq(windy.converged, true)
  T.check(doc:knots(p)[6][6][2] > still[2] + 1e-3, "the wind blows the net along +y")
  T.raises(function() doc:relax{wind = {direction = {0, 0, 0}, pressure = 1}} end, "relax:", "direction")
  T.raises(function() doc:relax{wind = {direction = {1, 0, 0}, pressure = -1}} end,
           "relax: argument 'wind.pressure' must be a number of N/m >= 0, got -1")
end)

T.done("test_api")
