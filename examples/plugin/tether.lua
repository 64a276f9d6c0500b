-- Purpose: loads the out-of-tree "tether" fix (examples/plugin) and checks it: a node on a
-- tether of stiffness k oscillates with omega = sqrt(k/m); after a quarter period from rest
-- at x = 1 it passes the anchor.
-- Expected run time: < 1 s (after building the plugin, see CMakeLists.txt here).
--   slender tether.lua -v plugin=build/libtether.so
local slender = require("slender")
local n = slender.plugin(slender.var("plugin", "build/libtether.so"))
print("plugin styles registered: " .. n)
local sim = slender.simulation { dimension = 3, quiet = true }
sim:wire { name = "w", points = { { 1, 0, 0 }, { 5, 0, 0 } } }
sim:group("bead", { chain = "w", nodes = { 1 } })
local k = 4.0
sim:fix("t", "tether", { group = "bead", point = { 0, 0, 0 }, k = k })
sim:integrator("verlet", { dt = 1e-4 })
local quarter = math.pi / 2 / math.sqrt(k)
sim:run(math.floor(quarter / 1e-4 + 0.5))
local x = sim:position(1)
print(string.format("x after a quarter period: %.2e", x))
assert(math.abs(x) < 1e-3, "the tether does not oscillate with sqrt(k/m)")
print("tether plugin: ok")
