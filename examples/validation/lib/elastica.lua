-- Reference solutions for the 2D validation decks, computed here and now (no tables).
--
-- Extensible elastica of a cantilever clamped at s = 0 along +x with a dead load P
-- along -y at the tip. With s the reference arclength, theta the tangent angle,
-- eps = N/EA the axial strain (N = -P sin(theta), tension > 0):
--   EI theta' = -P (x_L - x(s))  =>  EI theta'' = P (1 + eps) cos(theta),
--   x' = (1 + eps) cos(theta),  y' = (1 + eps) sin(theta),
-- with theta(0) = 0 and theta'(L) = 0. We shoot on theta'(0) with RK4 and bisection.
local M = {}

local function integrate(c, P, EI, EA, L, n)
  local h = L / n
  local th, x, y, k = 0.0, 0.0, 0.0, c
  local function f(th_, k_)
    local eps = -P * math.sin(th_) / EA
    return k_, (1 + eps) * math.cos(th_), (1 + eps) * math.sin(th_), P * (1 + eps) * math.cos(th_) / EI
  end
  for _ = 1, n do
    local a1, b1, c1, d1 = f(th, k)
    local a2, b2, c2, d2 = f(th + 0.5 * h * a1, k + 0.5 * h * d1)
    local a3, b3, c3, d3 = f(th + 0.5 * h * a2, k + 0.5 * h * d2)
    local a4, b4, c4, d4 = f(th + h * a3, k + h * d3)
    th = th + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
    x = x + h / 6 * (b1 + 2 * b2 + 2 * b3 + b4)
    y = y + h / 6 * (c1 + 2 * c2 + 2 * c3 + c4)
    k = k + h / 6 * (d1 + 2 * d2 + 2 * d3 + d4)
  end
  return x, y, k
end

-- Tip position (x, y) of the loaded cantilever. EA = math.huge gives the classic
-- inextensible elastica.
function M.cantilever_tip(P, EI, EA, L, steps)
  steps = steps or 2000
  if P == 0 then return L, 0 end
  -- theta'(0) = -P x_L / EI lies in [-P L (1 + P/EA) / EI, 0]
  local lo, hi = -1.01 * P * L * (1 + P / EA) / EI, 0.0
  local _, _, klo = integrate(lo, P, EI, EA, L, steps)
  for _ = 1, 80 do
    local mid = 0.5 * (lo + hi)
    local _, _, km = integrate(mid, P, EI, EA, L, steps)
    if (km < 0) == (klo < 0) then lo, klo = mid, km else hi = mid end
  end
  local x, y = integrate(0.5 * (lo + hi), P, EI, EA, L, steps)
  return x, y
end

-- Euler buckling loads of a column of length L. With a finite axial stiffness EA
-- the column is shortened by P/EA before it buckles; linearising EI theta' = M with
-- y' = (1 - P/EA) theta gives P (1 - P/EA) = P_Euler, the smaller root of which is
-- returned (EA = math.huge gives the classic load).
function M.euler_load(bc, EI, L, EA)
  local pe
  if bc == "pinned" then pe = math.pi ^ 2 * EI / L ^ 2
  elseif bc == "clamped" then pe = math.pi ^ 2 * EI / (4 * L ^ 2)
  else error("bc must be 'pinned' (pinned-pinned) or 'clamped' (clamped-free)", 2) end
  if not EA or EA == math.huge then return pe end
  return 0.5 * EA * (1 - math.sqrt(1 - 4 * pe / EA))
end

-- Maps the integrator names of the validation sweeps to slender styles.
function M.integrator(sim, name, dt)
  local p = { dt = dt }
  if name == "verlet" then sim:integrator("verlet", p)
  elseif name == "gear5" then p.values = 5; sim:integrator("gear", p)
  elseif name == "gear6" then p.values = 6; sim:integrator("gear", p)
  elseif name == "gear4" then p.values = 4; sim:integrator("gear", p)
  elseif name == "fire" then sim:integrator("fire", p)
  -- Newton statics (docs/models.md §9.3) needs no time stepper; verlet stands by
  elseif name == "newton" then sim:integrator("verlet", p)
  else error("integrator must be verlet, gear4, gear5, gear6, fire or newton, got " .. tostring(name), 2) end
end

-- Relaxes to static equilibrium: FIRE (or Newton) minimisation until the largest nodal
-- force is below tol, or damped dynamics until the kinetic energy is below ke_tol at two
-- checks in a row. (In damped dynamics the net force includes the drag, so a slowly
-- creeping overdamped mode has a small net force long before equilibrium; the
-- kinetic energy has no such blind spot.) Returns the steps taken.
function M.relax(sim, name, tol, max_steps, ke_tol)
  if name == "fire" or name == "newton" then
    local steps, ok = sim:minimize { ftol = tol, max_steps = max_steps, method = name }
    assert(ok, name .. " did not converge in " .. max_steps .. " steps")
    return steps
  end
  local start, below = sim:step(), 0
  sim:run { steps = max_steps, every = 500, callback = function(s)
    if s:value("ke") < ke_tol then below = below + 1 else below = 0 end
    return below >= 2
  end }
  assert(below >= 2, "dynamic relaxation did not converge in " .. max_steps .. " steps")
  return sim:step() - start
end

return M
