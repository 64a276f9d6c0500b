local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = 10 }
sim:group("tip", { chain = "w", nodes = { -1 } })
-- a second definition would leave styles set up on the first one without a word
sim:group("tip", { chain = "w", nodes = { 1 } })
