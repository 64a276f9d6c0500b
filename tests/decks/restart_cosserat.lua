-- Checkpoint/restart of a quaternion Cosserat rod (rod/cosserat): the quaternions,
-- their velocities and Gear's history of them come back, so a restarted run
-- continues bit-identically; the integrator may be declared before or after the rod.
local function scene(integ, integrator_first)
  local sim = slender.simulation { dimension = 3, seed = 3, quiet = true }
  sim:wire { name = "r", nodes = 12, spacing = 1, direction = { 1, 0, 0 }, perturb = 0.05 }
  local function integrator()
    if integ == "gear" then sim:integrator("gear", { values = 6, dt = 0.002 })
    else sim:integrator("verlet", { dt = 0.004 }) end
  end
  if integrator_first then integrator() end
  sim:bond("spring", { k = 300 })
  sim:bond("rod/cosserat", { YI = 2, GJ = 1.5, coupling = 100, rot_inertia = 0.2,
                             rest_curvature = { 0.1, 0.3, 0.05 }, rot_damping = 0.1 })
  if not integrator_first then integrator() end
  return sim
end

for _, integ in ipairs { "verlet", "gear" } do
  for _, first in ipairs { true, false } do
    local a = scene(integ, first)
    a:run(400)
    a:write_checkpoint("restart_cosserat.h5")
    a:run(400)
    local b = scene(integ, first)
    b:read_checkpoint("restart_cosserat.h5")
    b:run(400)
    local moved = 0
    for i = 1, a:nnodes() do
      local ax, ay, az = a:position(i)
      local bx, by, bz = b:position(i)
      assert(ax == bx and ay == by and az == bz,
             string.format("%s: node %d differs after restart", integ, i))
      moved = math.max(moved, math.abs(ay))
    end
    assert(moved > 1e-3, integ .. ": the rod did not curl")
    print(string.format("%s (integrator %s): restart bit-identical, |y| up to %.3f", integ,
                        first and "first" or "last", moved))
  end
end
print("cosserat restart: ok")
