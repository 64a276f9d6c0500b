local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 10 }
sim:group("w", { chain = "w", nodes = { 1, 2 } })
