local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4 }
sim:bond("spring", { k = 10 })
sim:group("root", { chain = "w", nodes = { 1, 2 } })
sim:fix("hold", "clamp", { group = "root" })
-- a clamp has no load to scale: the message names the fix and the styles that have one
sim:continuation { load = "hold" }
