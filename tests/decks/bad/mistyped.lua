local sim = slender.simulation { dimension = 2 }
sim:wire { name = "w", nodes = 10 }
sim:bond("spring", { k = 100 })
sim:bond("bend2d", { k = "stiff" })
