-- Benchmark of the shell family: FIRE steps of a growing e-cone disc (phi_e = 2 from flat)
-- at a given mesh size, with and without self-contact; prints element-steps/s.
--   build/slender scripts/bench_shell.lua -v edge=0.03125 -v steps=500
-- Measured here (6144 triangles, 2 cores shared with other jobs): shell alone 2.7 ms/step
-- (2.3e6 element-steps/s), with contact (dense = closest) 7.8 ms/step.
local slender = require("slender")
local edge = slender.var("edge", 1 / 32)
local steps = slender.var("steps", 500)
for _, contact in ipairs({ false, true }) do
  local sim = slender.simulation { dimension = 3, quiet = true }
  local _, tris = sim:mesh { name = "disc", shape = "disc", radius = 1, edge = edge, noise = 1e-4 }
  sim:growth("g", "econe", { phi_e = 2 })
  sim:shell("koiter", { mesh = "disc", thickness = 0.02, growth = "g", boundary = "mirror" })
  if contact then
    sim:pair("contact/shell", { mesh = "disc", thickness = 0.02, dense = slender.var("dense", "closest") })
  end
  sim:integrator("fire", {})
  sim:run(1)
  local t0 = slender.clock()
  sim:run(steps)
  local wall = slender.clock() - t0
  slender.result { triangles = tris, contact = contact, steps = steps, ms_per_step = 1000 * wall / steps,
                   element_steps_per_s = tris * steps / wall }
end
