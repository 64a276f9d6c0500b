-- A shell mesh read from a file that is wrong (tests/decks/bad/meshes/, chosen by -v mesh=):
-- one line naming the file, the line and what is wrong, before anything runs.
local here = debug.getinfo(1, "S").source:match("^@(.*/)") or "./"
local sim = slender.simulation { dimension = 3, quiet = true }
sim:mesh { name = "s", file = slender.var("mesh", here .. "meshes/unreferenced.obj") }
sim:run(1)
