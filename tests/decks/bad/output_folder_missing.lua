-- An output file in a folder that does not exist: one line saying so, no HDF5 trace.
local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 5, spacing = 1 }
sim:bond("spring", { k = 1 })
sim:integrator("verlet", { dt = 0.01 })
sim:dump("traj", "h5md", { file = "no_such_folder/traj.h5", every = 1 })
sim:run(2)
