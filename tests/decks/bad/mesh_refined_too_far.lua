-- A disc that each generator step allows, refined six more times: 6e9 triangles
local sim = slender.simulation { dimension = 3, quiet = true }
sim:mesh { name = "s", shape = "disc", radius = 1, edge = 0.01, refine = 6 }
