local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4 }
sim:integrator("verlet", { dt = 0.01 })
-- written only when the guard fires: refused here, not hours later
sim:guard { last_good_file = "no_such_folder/last_good.h5" }
sim:run(1)
