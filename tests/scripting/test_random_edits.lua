-- Random edit sequences through the Lua API (fixed seeds: Lua's generator gives the same
-- sequence on every machine), valid and invalid values mixed: wrong types, NaN, infinities,
-- removed handles. After every call:
-- - a refused one raised a message and left the sculpture's hash, its undo state and the
--   session's journal as they were;
-- - an accepted one that changed the sculpture undoes to the hash before it and redoes to the
--   hash after it.
-- Every few calls the sculpture is relaxed by a backend drawn at random (with wind or not),
-- reported, exported, saved as a journal and as a snapshot, and both reopen to its hash.
local T = require "testlib"
local ns = require "netsculpt"

local R = math.random
local function pick(t) return t[R(#t)] end

-- Values a careless script passes where a number or handle is expected.
local wild = {0, -1, 1e9, -1e9, 0 / 0, 1 / 0, -1 / 0, 2 ^ 53, 0.5, "x", "", {}, true, 1e-300}
local function maybe(v) if R() < 0.03 then return pick(wild) end return v end

-- Under `netsculpt run` every document made (ns.new, ns.open) is journaled to the output folder,
-- the first to <script>.netj, the n-th to <script>.n.netj; under a stock lua5.4 none is.
local stem = debug.getinfo(1, "S").source:gsub("^@", ""):match("([^/\\]+)%.lua$")
local underRun = not pcall(os.execute) -- the sandbox of `netsculpt run` refuses it
local made = 0
local function journaled(document)
  made = made + 1
  return document
end
local function journalOf(n)
  if not underRun then return nil end
  return ns.output_dir() .. "/" .. stem .. (n > 1 and ("." .. n) or "") .. ".netj"
end
local function sizeOf(path)
  local f = path and io.open(path, "rb")
  if not f then return nil end
  local size = f:seek("end")
  f:close()
  return size
end

local function editor(doc)
  local function rail()
    local rails = doc:rails()
    if #rails == 0 or R() < 0.05 then return maybe(R(5)) end
    return pick(rails)
  end
  local function piece()
    local pieces = doc:pieces()
    if #pieces == 0 or R() < 0.05 then return maybe(R(9)) end
    return pick(pieces)
  end
  local function whole(lo, hi) return maybe(R(lo, hi)) end
  local function length() return maybe(0.05 + R() * 0.4) end
  local function point() return {maybe(R() * 4 - 2), maybe(R() * 4 - 2), maybe(3 + R() * 3)} end
  local function points(lo, hi)
    local p = {}
    for i = 1, R(lo, hi) do p[i] = point() end
    return p
  end
  local gears = {1, 2, 3, 0.5, 1 / 3, "1/2", "x2", "/3"}
  return {
    function() return doc:add_rail{name = "r", points = points(2, 8), closed = R() < 0.5} end,
    function()
      return doc:add_rail{degree = maybe(R(1, 4)), control = points(3, 7), closed = R() < 0.5}
    end,
    function()
      return doc:attach_to_rail{rail = rail(), columns = whole(2, 30), rows = whole(1, 12),
                                bar = length(), at = maybe(R() < 0.5 and 0 or R())}
    end,
    function()
      return doc:attach_to_piece{piece = piece(), gear = maybe(pick(gears)), rows = whole(1, 10),
                                 bar = length()}
    end,
    function() return doc:split{piece = piece(), column = whole(0, 30)} end,
    function() return doc:set_rows{piece = piece(), rows = whole(1, 15)} end,
    function() return doc:set_columns{piece = piece(), columns = whole(2, 40)} end,
    function() return doc:set_gear{piece = piece(), gear = maybe(pick(gears))} end,
    function()
      return doc:set_bar_length{piece = piece(), column = whole(0, 30), length = length()}
    end,
    function()
      return doc:set_bar_length{piece = piece(), row = whole(0, 12), length = length()}
    end,
    function() return doc:set_bar_length{piece = piece(), length = length()} end,
    function()
      return doc:connect_to_rail{piece = piece(), rail = rail(), at = maybe(R()),
                                 reverse = R() < 0.3}
    end,
    function() return doc:disconnect{piece = piece()} end,
    function()
      return doc:set_material{piece = piece(), stiffness = maybe(10 ^ R(1, 6)),
                              compression_ratio = maybe(R())}
    end,
    function() return doc:set_colour{piece = piece(), colour = {maybe(R()), R(), R()}} end,
    function() return doc:rename{piece = piece(), name = maybe("p" .. R(9))} end,
    function() return doc:remove_piece(piece()) end,
    function() return doc:remove_rail(rail()) end,
    function() return doc:set_gravity{maybe(0), maybe(0), maybe(-9.81 * R())} end,
  }
end

-- Relaxes, reports, exports and saves `doc`, and reopens what was saved.
local function roundTrip(doc, seed, step)
  local options = {max_seconds = 0.5, tolerance = 1e-3,
                   backend = pick({"auto", "fast", "rk4", "bullet"})}
  if R() < 0.3 then options.wind = {direction = {1, 0, 0}, pressure = R()} end
  local ok, result = pcall(doc.relax, doc, options)
  if ok then
    T.check(result.residual == result.residual, "a relaxation's residual is not a number")
  else
    T.check(tostring(result):find("relax", 1, true), "relax failed without saying so: " ..
            tostring(result))
  end
  T.check(type(doc:report().total_weight) == "number")
  doc:export("random-edits.svg")
  doc:export("random-edits.glb")
  local saved = doc:save("random-edits.netj")
  T.eq(journaled(ns.open(saved)):hash(), doc:hash(),
       "the saved journal reopens to another sculpture (seed " .. seed .. ", call " .. step .. ")")
  local snapshot = doc:save_snapshot("random-edits.nets")
  T.eq(journaled(ns.open(snapshot)):hash(), doc:hash(), "the snapshot reopens to another sculpture")
end

local function run(seed, calls)
  math.randomseed(seed)
  local doc = journaled(ns.new())
  local journal = journalOf(made)
  local edits = editor(doc)
  local accepted, changed = 0, 0
  for step = 1, calls do
    local hash, canUndo, canRedo, size = doc:hash(), doc:can_undo(), doc:can_redo(), sizeOf(journal)
    local ok, message = pcall(edits[R(#edits)])
    local where = " (seed " .. seed .. ", call " .. step .. ")"
    if ok then
      accepted = accepted + 1
      local after = doc:hash()
      if after ~= hash then
        changed = changed + 1
        T.check(doc:can_undo(), "a change that cannot be undone" .. where)
        doc:undo()
        T.eq(doc:hash(), hash, "undo did not restore the sculpture" .. where)
        doc:redo()
        T.eq(doc:hash(), after, "redo did not restore the edit" .. where)
      end
    else
      T.check(type(message) == "string" and #message > 0, "a refusal without a message" .. where)
      T.eq(doc:hash(), hash, "a refused call changed the sculpture: " .. message .. where)
      T.eq(doc:can_undo(), canUndo, "a refused call changed what can be undone" .. where)
      T.eq(doc:can_redo(), canRedo, "a refused call changed what can be redone" .. where)
      T.eq(sizeOf(journal), size, "a refused call wrote to the journal" .. where)
    end
    if step % 60 == 0 and #doc:pieces() > 0 then roundTrip(doc, seed, step) end
    if R() < 0.05 and doc:can_undo() then doc:undo() end
  end
  T.check(not underRun or sizeOf(journal), "no journal at " .. tostring(journal))
  -- Enough of both kinds for the checks to mean something.
  T.check(changed >= calls // 5, "seed " .. seed .. ": only " .. changed .. " calls changed it")
  T.check(calls - accepted >= calls // 5, "seed " .. seed .. ": only " .. (calls - accepted) ..
          " calls were refused")
end

for _, seed in ipairs({2, 11, 47}) do
  T.case("random edits, seed " .. seed, function() run(seed, 240) end)
end

T.done("test_random_edits")
