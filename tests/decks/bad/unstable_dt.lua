-- A stiff wire run with dt far above the stable step: the guard must stop the
-- run, name the stable dt and leave no NaN in the outputs.
local sim = slender.simulation { dimension = 2, seed = 3 }
sim:wire { name = "w", nodes = 30, spacing = 1, perturb = 0.05 }
sim:bond("spring", { k = 1000 })
sim:bond("bend2d", { k = 60 })
sim:integrator("verlet", { dt = 0.2 })  -- stable limit is 2/omega ~ 0.03
sim:thermo { every = 5, columns = { "step", "ke", "pe" }, file = "thermo.csv" }
sim:dump("traj", "h5md", { file = "traj.h5", every = 5 })
sim:run(10000)
