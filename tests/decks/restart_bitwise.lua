-- Checkpoint/restart: a run interrupted by a checkpoint continues bit-identically.
-- Two scenes in one process (there is no global state), for each integrator.
local function scene(integ)
  local sim = slender.simulation { dimension = 2, seed = 42, quiet = true }
  sim:wire { name = "w", nodes = 40, spacing = 1, perturb = 0.1 }
  sim:bond("spring", { k = 1000 })
  sim:bond("bend2d", { k = 60 })
  sim:group("tip", { chain = "w", nodes = { -1 } })
  sim:group("base", { chain = "w", nodes = { 1 } })
  sim:fix("hold", "clamp", { group = "base", rotation = true })
  sim:fix("push", "force/constant", { group = "tip", force = { -1, 0.5 }, rate = { 0, 0.01 } })
  sim:fix("drag", "damping/viscous", { gamma = 0.01 })
  sim:fix("wall", "wall/circle", { radius = 25, center = { 20, 0 }, stiffness = 1e4, exponent = 2, diameter = 1 })
  if integ == "gear" then sim:integrator("gear", { values = 5, dt = "auto" })
  elseif integ == "fire" then sim:integrator("fire", {})
  else sim:integrator("verlet", { dt = 0.01 }) end
  return sim
end

for _, integ in ipairs { "verlet", "gear", "fire" } do
  local a = scene(integ)
  a:run(300)
  a:write_checkpoint("restart_" .. integ .. ".h5")
  a:run(300)

  local b = scene(integ)
  b:read_checkpoint("restart_" .. integ .. ".h5")
  assert(b:step() == 300, "restored step")
  b:run(300)

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
