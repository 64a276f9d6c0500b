-- A wall too small for the wire it holds: refused at its deck line, naming both sizes.
local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 4, spacing = 0.1 }
sim:fix("cavity", "wall/circle", { radius = 0.4, diameter = 1.0, stiffness = 100 })
