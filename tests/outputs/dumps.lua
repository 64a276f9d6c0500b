-- Every dump kind, small, for the ParaView reader test (tests/outputs/test_paraview.py):
-- -v kind=wire2d: a closed ring and an open wire in 2D (h5md), three frames in time, inside a
--   circular wall with two openings (its own XDMF file: two arcs);
-- -v kind=wire3d: an open rod in 3D (h5md) with a node property field, in a sphere (three
--   great circles);
-- -v kind=shell: a shell disc relaxed twice by FIRE, one frame after each (the clock does not
-- move during a minimisation, so both frames carry the same time).
local kind = slender.var("kind", "wire2d")
if kind == "wire2d" then
  local sim = slender.simulation { dimension = 2, quiet = true }
  sim:wire { name = "ring", radius = 3, nodes = 30, closed = true }
  sim:wire { name = "open", nodes = 8, spacing = 0.5, start = { -2, 0 } }
  sim:bond("spring", { k = 100 })
  sim:fix("cavity", "wall/circle", { radius = 8, stiffness = 100, openings = { 0, math.pi } })
  sim:integrator("verlet", { dt = 0.01 })
  sim:dump("traj", "h5md", { file = "wire2d.h5", every = 5, fields = { "position", "velocity" } })
  sim:run(10)
elseif kind == "wire3d" then
  local sim = slender.simulation { dimension = 3, quiet = true }
  sim:wire { name = "rod", nodes = 12, spacing = 0.5, start = { 0, 0, 0 }, direction = { 0, 0, 1 } }
  sim:bond("spring", { k = 100 })
  sim:bond("rod/straight", { YI = 1 })
  sim:fix("cavity", "wall/sphere", { radius = 8, stiffness = 100 })
  sim:integrator("verlet", { dt = 0.01 })
  sim:dump("traj", "h5md", { file = "wire3d.h5", every = 5, fields = { "position", "force" } })
  sim:run(10)
else
  local sim = slender.simulation { dimension = 3, quiet = true }
  sim:mesh { name = "disc", shape = "disc", radius = 1, edge = 0.25 }
  sim:shell("koiter", { mesh = "disc", thickness = 0.05, young = 1e4 })
  sim:growth("g", "isotropic", { factor = 1.05 })
  sim:integrator("fire", {})
  sim:dump("surface", "shell", { file = "shell.h5", every = 1000000000, mesh = "disc",
                                 faces = { "koiter.Ub" } })
  for _ = 1, 2 do
    sim:minimize { ftol = 1e-3, max_steps = 50 }
    sim:write_dump("surface")
  end
end
