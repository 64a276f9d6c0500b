-- Benchmark: node-steps per second of the 2D cantilever (spring + bend2d + clamp +
-- tip load + damping) for every integrator, measured in one run so the ratios
-- are comparable.   build/slender scripts/bench_cantilever.lua [-v nodes=1000 -v steps=20000]
local N = slender.var("nodes", 1000)
local steps = slender.var("steps", 20000)
local L, EI, EA = 1.0, 1.0, 1e5
local h = L / (N - 0.5)

local function scene(integ)
  local sim = slender.simulation { dimension = 2, quiet = true }
  sim:wire { name = "beam", nodes = N + 1, spacing = h, start = { -h / 2, 0 }, mass = h }
  sim:bond("spring", { k = EA / h })
  sim:bond("bend2d", { k = EI / h })
  sim:group("base", { chain = "beam", nodes = { 1, 2 } })
  sim:group("tip", { chain = "beam", nodes = { -1 } })
  sim:fix("clamp", "clamp", { group = "base" })
  sim:fix("load", "force/constant", { group = "tip", force = { 0, -3 } })
  sim:fix("drag", "damping/viscous", { gamma = 7 * h })
  if integ == "verlet" then sim:integrator("verlet", {})
  elseif integ == "fire" then sim:integrator("fire", {})
  else sim:integrator("gear", { values = tonumber(integ:sub(5)) }) end
  return sim
end

print(string.format("%-8s %8s %10s %12s %14s", "integ", "nodes", "steps", "wall_s", "node-steps/s"))
for _, integ in ipairs { "verlet", "gear4", "gear5", "gear6", "fire" } do
  local sim = scene(integ)
  sim:run(100)  -- warm-up (allocations, first force evaluation)
  local t0 = slender.clock()
  sim:run(steps)
  local wall = slender.clock() - t0
  local rate = (N + 1) * steps / wall
  print(string.format("%-8s %8d %10d %12.3f %14.4g", integ, N + 1, steps, wall, rate))
  slender.result { case = "bench_cantilever", integrator = integ, nodes = N + 1, steps = steps, wall_s = wall,
    node_steps_per_s = rate }
end
