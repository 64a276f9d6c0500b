-- Checkpoint/restart: a run interrupted by a checkpoint continues bit-identically.
-- Two scenes in one process (there is no global state), for each integrator.
local function scene(integ)
  local sim = slender.simulation { dimension = 2, seed = 42, quiet = true }
  -- the first node presses on the wall (friction history from the start); the
  -- pushed tip folds the wire onto itself (node-edge contacts with friction)
  sim:wire { name = "w", nodes = 25, spacing = 1, perturb = 0.1, start = { 5.4, 0 } }
  sim:bond("spring", { k = 1000 })
  sim:bond("bend2d", { k = 60 })
  sim:group("tip", { chain = "w", nodes = { -1 } })
  sim:group("base", { chain = "w", nodes = { 1 } })
  sim:fix("hold", "clamp", { group = "base", rotation = true })
  sim:fix("push", "force/constant", { group = "tip", force = { -20, 4 }, rate = { 0, 0.5 } })
  sim:fix("drag", "damping/viscous", { gamma = 0.01 })
  sim:fix("wall", "wall/circle", { radius = 15, center = { 20, 0 }, stiffness = 1e4, exponent = 2, diameter = 1,
                                   mu_static = 0.4, damping = 5 })
  sim:pair("contact/node-edge", { stiffness = 1e4, damping = 5, mu_static = 0.3 })
  if integ == "gear" then sim:integrator("gear", { values = 5, dt = 0.004 })
  elseif integ == "fire" then sim:integrator("fire", {})
  else sim:integrator("verlet", { dt = 0.01 }) end
  return sim
end

for _, integ in ipairs { "verlet", "gear", "fire" } do
  local a = scene(integ)
  local wall, pair = 0, 0
  local function count(s)
    wall = math.max(wall, s:value("wall.contacts"))
    pair = math.max(pair, s:value("contact/node-edge.contacts"))
  end
  local half = integ == "gear" and 1000 or 300  -- gear's dt is smaller
  a:run { steps = half, every = 10, callback = count }
  a:write_checkpoint("restart_" .. integ .. ".h5")
  local measured = {}
  for _, key in ipairs { "wall.contacts", "wall.force", "contact/node-edge.contacts" } do
    measured[key] = a:value(key)
  end
  a:run { steps = half, every = 10, callback = count }
  print(string.format("%s: up to %d wall and %d wire-wire contacts", integ, wall, pair))
  assert(wall > 0 and (integ == "fire" or pair > 0), "the restart scene must exercise friction history")

  local b = scene(integ)
  b:read_checkpoint("restart_" .. integ .. ".h5")
  assert(b:step() == half, "restored step")
  -- the restored forces are not recomputed, so what was measured with them must come back
  -- too (the first thermo row of a restarted run printed 0 contacts)
  for key, v in pairs(measured) do
    assert(b:value(key) == v, string.format("%s: %s is %.17g after the restart, %.17g before", integ, key,
                                            b:value(key), v))
  end
  b:run(half)

  for i = 1, a:nnodes() do
    local ax, ay = a:position(i)
    local bx, by = b:position(i)
    assert(ax == bx and ay == by, string.format("%s: node %d differs after restart: %.17g vs %.17g", integ, i, ax, bx))
  end
  -- the uninterrupted run moved: a restart that lost the state would not match it
  local x0 = scene(integ)
  local moved = false
  for i = 1, a:nnodes() do
    local ax, ay = a:position(i)
    local cx, cy = x0:position(i)
    moved = moved or ax ~= cx or ay ~= cy
  end
  assert(moved, integ .. ": nothing moved")
  print(integ .. ": restart is bit-identical after " .. a:step() .. " steps")
end

-- the periodic checkpoint dump writes the same state atomically
local c = scene("gear")
c:dump("ck", "checkpoint", { file = "ck_%d.h5", every = 200 })
c:run(400)
local d = scene("gear")
d:read_checkpoint("ck_200.h5")
d:run(200)
local cx, cy = c:position(-1)
local dx, dy = d:position(-1)
assert(cx == dx and cy == dy, "checkpoint dump restart differs")
print("checkpoint dump: ok")
