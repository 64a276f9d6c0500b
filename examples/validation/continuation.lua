-- Purpose: equilibrium paths by pseudo-arc-length continuation (docs/models.md §9.4), with
-- their limit and bifurcation points against closed forms: -v case=truss follows a von
-- Mises truss through both limit points of its snap-through (P_max from P(w)); -v
-- case=column loads a straight clamped-free 2D column and finds Euler's bifurcation
-- P_cr = pi^2 EI / (4 L^2) from the count of negative pivots of the stiffness matrix, and
-- with -v branch=true follows the buckled branch against the elastica; -v case=roll rolls a
-- clamped wire into a full circle by an end moment (fix moment2d) against the exact arcs;
-- -v case=tip drives the cantilever's tip down by a prescribed motion (fix prescribe,
-- displacement control, §9.8) to w = 0.3 L, its reaction at small w against the
-- Euler-Bernoulli 3 EI w / L^3.
-- Expected run time: well under a second for either case (defaults).
--   slender continuation.lua -v case=column -v nodes=81
local case = slender.var("case", "truss")
assert(case == "truss" or case == "column" or case == "roll" or case == "tip",
       "case must be truss, column, roll or tip")
local check = slender.var("check")
local fast = slender.var("fast", false)  -- the suite's fast mode: a coarser column
local t0 = slender.clock()

-- the clamped cantilever of cantilever2d.lua (EI = 1, EA = 1e5, L = 1 from the staggered
-- clamp) as the chain `name` of N + 1 nodes: the tip, roll and column cases
local function cantilever(name)
  local N = slender.var("nodes", fast and 21 or 41)
  local h = 1.0 / (N - 0.5)
  local sim = slender.simulation { dimension = 2, seed = 1 }
  sim:wire { name = name, nodes = N + 1, spacing = h, start = { -h / 2, 0 }, direction = { 1, 0 }, mass = h }
  sim:bond("spring", { k = 1e5 / h })
  sim:bond("bend2d", { k = 1 / h })
  sim:group("base", { chain = name, nodes = { 1, 2 } })
  sim:fix("clamp", "clamp", { group = "base" })
  return sim, N
end

if case == "truss" then
  -- supports at (+-a, 0), apex at (0, h), springs k; the apex load lambda points down.
  -- Along the path P(w) = 2 k (L0 - L) (h - w) / L, L = sqrt(a^2 + (h - w)^2).
  local a, h, k = 1.0, slender.var("rise", 0.5), 100.0
  local L0 = math.sqrt(a * a + h * h)
  local function load(w)
    local L = math.sqrt(a * a + (h - w) ^ 2)
    return 2 * k * (L0 - L) * (h - w) / L
  end
  -- the analytic limit load, the maximum of P(w) over (0, h), by golden-section search
  local lo, hi = 0.0, h
  for _ = 1, 200 do
    local m1, m2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
    if load(m1) < load(m2) then lo = m1 else hi = m2 end
  end
  local pmax = load(0.5 * (lo + hi))
  local sim = slender.simulation { dimension = 2, seed = 1 }
  sim:wire { name = "truss", points = { { -a, 0 }, { 0, h }, { a, 0 } } }
  sim:bond("spring", { k = k })
  sim:group("supports", { chain = "truss", nodes = { 1, 3 } })
  sim:group("apex", { chain = "truss", nodes = { 2 } })
  sim:fix("hold", "clamp", { group = "supports" })
  sim:fix("push", "force/constant", { group = "apex", force = { 0, -1 } })
  local limits, worst = {}, 0.0
  local points, lambda = sim:continuation { load = "push", ds = 0.02, ds_max = 0.05, points = 2000,
    ftol = 1e-10, callback = function(s, p)
      local _, y = s:position(2)
      worst = math.max(worst, math.abs(p.lambda - load(h - y)) / pmax)
      if p.event then limits[#limits + 1] = p.critical_lambda end
      return h - y > 2.5 * h
    end }
  local err = math.max(math.abs(limits[1] - pmax), math.abs(limits[2] + pmax)) / pmax
  slender.result { case = "truss", points = points, lambda = lambda, limit_points = #limits,
    p_max = pmax, first_limit = limits[1], second_limit = limits[2], limit_error = err,
    path_error = worst, wall_s = slender.clock() - t0 }
  if check then
    assert(#limits == 2, "expected two limit points, found " .. #limits)
    assert(err < check and worst < check,
           string.format("limit error %.3e, path error %.3e exceed %.3e", err, worst, check))
  end
elseif case == "tip" then
  -- the cantilever of cantilever2d.lua (EI = 1, EA = 1e5, L = 1), its tip's y held on the
  -- path w = lambda 0.3 (x free); at the first points (w < 0.01 L) the reaction is the
  -- linear tip force 3 EI w / L^3, the discrete wire's error falling as h^2
  local sim, N = cantilever("beam")
  sim:group("tip", { chain = "beam", nodes = { -1 } })
  sim:fix("drive", "prescribe", { group = "tip", displacement = { 0, -0.3 }, components = "y" })
  local linear_error, events, last = nil, 0, 0.0
  local points, lambda = sim:continuation { load = "drive", ds = 0.002, ds_max = 0.05, lambda_max = 1,
    points = 500, ftol = 1e-8, callback = function(s, p)
      local w = 0.3 * p.lambda
      if p.event then events = events + 1 end
      if p.index > 0 and w < 0.01 and not linear_error then
        linear_error = math.abs(-s:value("drive.reaction_y") / (3 * w) - 1)
      end
      if p.lambda <= 1 then last = p.lambda end
    end }
  slender.result { case = "tip", nodes = N, points = points, lambda = lambda, rel_error = linear_error,
    events = events, last_lambda = last, wall_s = slender.clock() - t0 }
  if check then
    assert(events == 0, "displacement control crossed " .. events .. " critical points")
    assert(last > 0.9, "the path stopped at lambda = " .. last)
    assert(linear_error and linear_error < check,
           string.format("reaction error %s exceeds %.3e", tostring(linear_error), check))
  end
elseif case == "roll" then
  -- the cantilever of cantilever2d.lua under an end moment lambda M0, M0 = 2 pi EI / L: pure
  -- bending into an arc of curvature kappa = lambda M0 / EI, the tip at
  -- (sin(kappa L) / kappa, (1 - cos(kappa L)) / kappa); the circle closes at lambda = 1
  local sim, N = cantilever("beam")
  sim:fix("roll", "moment2d", { chain = "beam", moment = 2 * math.pi })
  local worst, last, closed = 0.0, 0.0, nil
  local points, lambda = sim:continuation { load = "roll", ds = 0.05, ds_max = 0.2, lambda_max = 1, points = 500,
    ftol = 1e-7, callback = function(s, p)
      if p.lambda > 1 or p.lambda <= 0 then return false end
      local kappa = 2 * math.pi * p.lambda
      local x, y = s:position(-1)
      worst = math.max(worst, math.sqrt((x - math.sin(kappa) / kappa) ^ 2 + (y - (1 - math.cos(kappa)) / kappa) ^ 2))
      last = p.lambda
    end }
  -- the closed circle: Newton at exactly lambda = 1, the tip back at the clamp
  sim:continuation { load = "roll", lambda0 = 1, points = 1, ds = 1e-9, ds_min = 1e-12, ftol = 1e-7,
    callback = function(s, p)
      if p.index == 0 then closed = { s:position(-1) } end
      return true
    end }
  local gap = math.sqrt(closed[1] ^ 2 + closed[2] ^ 2)
  slender.result { case = "roll", nodes = N, points = points, lambda = lambda, last_checked = last,
    arc_error = worst, closure_gap = gap, wall_s = slender.clock() - t0 }
  if check then
    assert(last > 0.8, "the path stopped at lambda = " .. last)
    assert(worst < check and gap < check,
           string.format("arc error %.3e, closure gap %.3e exceed %.3e", worst, gap, check))
  end
else
  -- the clamped cantilever of cantilever2d.lua (EI = 1, EA = 1e5, L = 1, staggered clamp)
  local sim, N = cantilever("column")
  sim:group("tip", { chain = "column", nodes = { -1 } })
  sim:fix("load", "force/constant", { group = "tip", force = { -1, 0 } })
  local pcr = math.pi ^ 2 / 4
  -- -v branch=true switches onto the buckled branch at P_cr and follows it to a tip
  -- deflection of 0.55 L, against the elastica: lambda / P_cr = (2 K(k) / pi)^2 where
  -- delta / L = 2 k / K(k), K the complete elliptic integral (by the AGM)
  local branch = slender.var("branch", false)
  local function K(k)
    local a, b = 1.0, math.sqrt(1 - k * k)
    for _ = 1, 30 do a, b = 0.5 * (a + b), math.sqrt(a * b) end
    return math.pi / (2 * a)
  end
  local function elastica_load(delta)
    local lo, hi = 0.0, 0.6
    for _ = 1, 100 do
      local k = 0.5 * (lo + hi)
      if 2 * k / K(k) < delta then lo = k else hi = k end
    end
    return pcr * (2 * K(0.5 * (lo + hi)) / math.pi) ^ 2
  end
  local found, on_branch, worst, checked = nil, false, 0.0, 0
  -- the axial shortening per unit load is L / EA = 1e-5: the first arc-length steps are of
  -- that order (they grow to ds_max; lambda_max stays below the second critical load 9 P_cr)
  local points = sim:continuation { load = "load", ds = 1e-5, ds_max = branch and 0.05 or 2e-5,
    lambda_max = 4, points = 2000, switch_branch = branch,
    callback = function(s, p)
      if p.event == "bifurcation point" then
        found, on_branch = p.critical_lambda, branch
        return false
      end
      if not on_branch then return false end
      local _, y = s:position(-1)
      if math.abs(y) > 0.05 then  -- away from the critical point
        worst = math.max(worst, math.abs(p.lambda - elastica_load(math.abs(y))) / pcr)
        checked = checked + 1
      end
      return math.abs(y) > 0.55
    end }
  local err = found and math.abs(found - pcr) / pcr or 1
  slender.result { case = "column", nodes = N, points = points, critical = found or -1, euler = pcr,
    rel_error = err, branch = branch, branch_points = checked, branch_error = worst,
    wall_s = slender.clock() - t0 }
  if check then
    assert(found, "no bifurcation point found below lambda = 4")
    assert(err < check, string.format("relative error %.3e exceeds %.3e", err, check))
    if branch then
      assert(checked >= 5 and worst < check,
             string.format("%d points on the branch, error %.3e (tolerance %.3e)", checked, worst, check))
    end
  end
end
