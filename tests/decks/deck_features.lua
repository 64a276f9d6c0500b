-- Lua control flow, callbacks, -v overrides, groups, regions and the rule that a
-- scene allocates only the node properties its styles ask for.
local n = slender.var("n", 10)
assert(n == 25, "the test passes -v n=25, got " .. tostring(n))
assert(slender.var("missing", "fallback") == "fallback")

local function has(list, name)
  for _, v in ipairs(list) do if v == name then return true end end
  return false
end

-- a plain elastic wire with Verlet: only the four core arrays
local sim = slender.simulation { dimension = 2, quiet = true }
sim:wire { name = "w", nodes = n, spacing = 1 }
sim:bond("spring", { k = 100 })
sim:integrator("verlet", { dt = 0.01 })
sim:run(10)
local props = sim:properties()
assert(#props == 4, "a bare wire holds " .. #props .. " arrays: " .. table.concat(props, " "))
assert(not has(props, "dof_mask") and not has(props, "gear.r2"))

-- Gear and a clamp bring exactly their own properties
local g = slender.simulation { dimension = 2, quiet = true }
g:wire { name = "w", nodes = n, spacing = 1 }
g:bond("spring", { k = 100 })
g:group("first", { chain = "w", nodes = { 1 } })
g:fix("hold", "clamp", { group = "first" })
g:integrator("gear", { values = 6 })
local gp = g:properties()
assert(has(gp, "dof_mask") and has(gp, "gear.r5") and not has(gp, "gear.r6"), table.concat(gp, " "))

-- groups by region; callbacks see the live scene and can stop the run
g:region("left", "box", { lo = { -1, -1 }, hi = { 4.5, 1 } })
assert(g:group("left_nodes", { region = "left" }) == 5)
g:group("last", { chain = "w", nodes = { -1 } })
g:fix("pull", "force/constant", { group = "last", force = { 5, 0 } })
g:compute("count", "count", {})
local calls = 0
g:run { steps = 100000, every = 10, callback = function(s)
  calls = calls + 1
  local x = s:position(-1)
  return x > n - 1 + 0.02   -- stop once the end moved by 0.02
end }
assert(calls > 0 and g:step() < 100000, "callback did not stop the run")
assert(g:value("count.nodes") == n)
-- a tip force F on a chain of springs k stretches the last edge by F/k
local x = g:position(-1)
print(string.format("stopped at step %d after %d callbacks, tip x = %.4f", g:step(), calls, x))

-- the same seed gives the same random start, another seed another one
local function start(seed)
  local s = slender.simulation { dimension = 2, seed = seed, quiet = true }
  s:wire { name = "w", nodes = 20, perturb = 0.1 }
  local _, y = s:position(7)
  return y
end
assert(start(5) == start(5) and start(5) ~= start(6), "seeded random stream")
-- thermo append: a restarted run continues the CSV under a single header
local function thermo_run(append)
  local s = slender.simulation { dimension = 2, quiet = true }
  s:wire { name = "w", nodes = 5 }
  s:bond("spring", { k = 10 })
  s:integrator("verlet", { dt = 0.01 })
  s:thermo { every = 5, file = "append_thermo.csv", columns = { "step", "ke" }, console = false,
             append = append }
  s:run(10)
end
thermo_run(false)
thermo_run(true)
local lines, headers = 0, 0
for line in io.lines("append_thermo.csv") do
  lines = lines + 1
  if line:match("^step") then headers = headers + 1 end
end
assert(headers == 1 and lines == 1 + 2 * 3, "append: " .. headers .. " headers, " .. lines .. " lines")
thermo_run(false)
lines = 0
for _ in io.lines("append_thermo.csv") do lines = lines + 1 end
assert(lines == 4, "without append the CSV is replaced: " .. lines .. " lines")
-- rod frames: set from directors before the first run (kept by the rod's setup), read
-- back as a quaternion and directors; a twisted start holds twist energy
local rod = slender.simulation { dimension = 3, quiet = true }
rod:wire { name = "r", points = { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 3, 0, 0 } } }
rod:bond("spring", { k = 100 })
rod:bond("rod/cosserat", { YI = 1, GJ = 1, coupling = 20, rot_inertia = 0.1 })
local a = 0.3
rod:set_frame(3, { d1 = { 0, math.cos(a), math.sin(a) }, d3 = { 1, 0, 0 } })
rod:integrator("verlet", { dt = 1e-3 })
rod:run(0)
local fr = rod:frame(3)
assert(math.abs(fr.d1[2] - math.cos(a)) < 1e-12 and math.abs(fr.d1[3] - math.sin(a)) < 1e-12,
       "frame d1 read back: " .. table.concat(fr.d1, " "))
assert(math.abs(fr.d3[1] - 1) < 1e-12 and #fr.q == 4 and #fr.d2 == 3)
assert(rod:value("energy.twist") > 0, "a twisted start holds twist energy")
local ok, err = pcall(function() rod:frame(4) end)
assert(not ok and tostring(err):match("starts no edge"), tostring(err))
ok, err = pcall(function() rod:set_frame(1, { d1 = { 1, 0, 0 }, d3 = { 1, 0, 0 } }) end)
assert(not ok and tostring(err):match("right angles"), tostring(err))
print("deck features: ok")
