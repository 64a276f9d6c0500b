-- A contact radius of a million rest lengths: every pair along the wire would be excluded
local sim = slender.simulation { dimension = 3, quiet = true }
sim:wire { name = "w", nodes = 6, spacing = 1 }
sim:pair("contact/segment", { radius = 927777777777, stiffness = 100 })
