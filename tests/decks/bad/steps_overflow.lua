-- a step count past 2^53 (here 2^63): refused as too large, not as "negative" after an overflow
local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 3 }
sim:bond("spring", { k = 1 })
sim:integrator("verlet", { dt = 0.01 })
sim:run(2 ^ 63)
