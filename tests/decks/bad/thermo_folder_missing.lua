local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4 }
sim:integrator("verlet", { dt = 0.01 })
-- the message says why the file cannot be opened
sim:thermo { every = 1, columns = { "step" }, file = "no_such_folder/thermo.csv" }
sim:run(1)
