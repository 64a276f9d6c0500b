local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4 }
sim:integrator("verlet", { dt = 0.01 })
-- the message names the file asked for, not the temporary file written beside it
sim:write_checkpoint("no_such_folder/restart.h5")
