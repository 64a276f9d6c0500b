-- an isotropic growth whose factor reaches zero and below through its rate (1 - 1000 t):
-- det(G) = factor^2 stays positive, the run must still stop and name the growth
local sim = slender.simulation { dimension = 3, quiet = true }
sim:mesh { name = "r", shape = "rectangle", size = { 1.0, 0.5 }, edge = 0.25 }
sim:growth("g", "isotropic", { factor = 1, rate = -1000 })
sim:shell("koiter", { mesh = "r", thickness = 0.02, growth = "g", boundary = "mirror" })
sim:integrator("newmark", { dt = 0.0007 })
sim:run(5)
