-- The e-cone scene shared by econe.lua (S-1, S-4, S-5) and econe_stability.lua (S-2):
-- a free disc (or ring) growing circumferentially (docs/models.md §6.9), Koiter shell with
-- mirror ghosts, faceted self-contact, rim-mode analysis, L-BFGS (or FIRE) relaxations, a CSV log.
local slender = require("slender")
local M = {}

-- opts: fast, h, edge, out, mu_static (contact friction, 0: frictionless), and the defaults of
-- noise, mode and minimizer where a deck wants others; deck -v values override the defaults the
-- same way in every e-cone deck.
function M.build(opts)
  local fast = opts.fast
  local s = {}
  s.h = slender.var("h", 0.02)
  s.edge = slender.var("edge", fast and 0.125 or 0.0625)
  s.young, s.poisson = 1e4, 0.3
  -- equilibrium: largest nodal force below ftol_rel * Y h edge^2 (the deck's tolerance).
  -- The shape of a thin cone is set by bending forces (~ h^3), so below h = 0.02 the default
  -- falls as h^2: at h = 0.01 a fixed 1e-5 left the first contact uncertain by 0.02 in phi_e
  -- (L-BFGS (6.922, 6.925], FIRE (6.900, 6.903]; with 2.5e-6: (6.906, 6.909])
  s.ftol = slender.var("ftol_rel", 1e-5 * math.min(1, (s.h / 0.02) ^ 2)) * s.young * s.h *
           s.edge * s.edge
  s.max_steps = slender.var("max_steps", 200000)
  s.out = slender.var("out", opts.out)
  os.execute("mkdir -p " .. s.out)
  local sim = slender.simulation{dimension = 3, seed = slender.var("seed", 1)}
  s.sim = sim
  s.inner = slender.var("inner", 0)
  local noise = slender.var("noise", opts.noise or 1e-4)  -- out-of-plane noise amplitude (docs/models.md §6.12)
  if s.inner > 0 then
    s.nodes, s.tris = sim:mesh{name = "disc", shape = "ring", radius = 1, inner_radius = s.inner,
                               edge = s.edge, noise = noise}
  else
    s.nodes, s.tris = sim:mesh{name = "disc", shape = "disc", radius = 1, edge = s.edge,
                               noise = noise, refine_center = slender.var("refine_center", 0),
                               refine_levels = slender.var("refine_levels", 0)}
  end
  -- an initial shape with n wings (S-5), on top of the random noise
  local mode, mode_amp = slender.var("mode", opts.mode or 0), slender.var("mode_amp", 1e-3)
  if mode > 0 then
    for i = 1, s.nodes do
      local x, y, z = sim:position(i)
      local r, a = math.sqrt(x * x + y * y), math.atan(y, x)
      sim:set_position(i, {x, y, z + mode_amp * r * r * math.cos(mode * a)})
    end
  end
  sim:growth("g", "econe", {phi_e = 0})
  sim:shell("koiter", {mesh = "disc", thickness = s.h, young = s.young, poisson = s.poisson,
                       growth = "g", boundary = slender.var("boundary", "mirror")})
  -- near neighbours within 4 h in the reference never touch (-v near_contact=ridge: only across
  -- a ridge, docs/models.md §6.10): the core of a thick cone is tighter than h, its faceted layers
  -- come within h of each other across the tip, and a force that switches on with the sign
  -- of n1.n2 stalled FIRE there (h = 0.04, edge 1/16: |f| stuck at 0.14 at phi_e = 6.2 and
  -- E_s doubled; without it the same state relaxes in 4 600 steps). The kissing
  -- angle counts only contacts between triangles more than R/4 apart in the reference (the
  -- wings): the sharp apex of a thick cone touches itself across the tip long before.
  -- dense = "all" sums the forces of every feature pair within h: relaxations after contact
  -- converge (with the closest pair only, FIRE stalls where the closest feature switches)
  -- -v contact=0: no self-contact (the self-intersecting companion branch of S-2)
  s.contact = slender.var("contact", 1) == 1
  s.far_distance = slender.var("far_distance", 0.25)
  if s.contact then
    sim:pair("contact/shell", {mesh = "disc", thickness = s.h, young = s.young,
                               near_distance = slender.var("near_distance", 4 * s.h),
                               near_contact = slender.var("near_contact", "never"),
                               far_distance = s.far_distance,
                               dense = slender.var("dense", "all"),
                               -- the list is rebuilt whenever a node has moved half the skin;
                               -- the periodic rebuild on top of it cost 20 % of an L-BFGS ramp
                               rebuild_every = slender.var("rebuild_every", 1000),
                               mu_static = opts.mu_static or 0})
  end
  -- contact observables, also without contact (0 contacts, gamma -1)
  function s.cv(key)
    if s.contact then return sim:value("contact/shell." .. key) end
    return key == "gamma" and -1 or 0
  end
  -- the smallest distance between the mid-surfaces of far parts (the wings), so the kiss can be
  -- read both ways: contact at distance h, or mid-surfaces touching (-v contact=0); searched
  -- up to 4 h (the column reads 4 h when the wings are farther apart)
  sim:compute("gap", "far_distance", {mesh = "disc", far_distance = s.far_distance, reach = 4 * s.h})
  sim:compute("rim", "rim_modes", {group = "disc.boundary", min_radius = 0.5 * (1 + s.inner)})
  -- core radius R_C (docs/models.md §6.11 [C]): the bending energy inside r grows as A ln(r / R_C)
  -- on the developable range 0.3 <= r <= 0.6 (R_C), and where the ring-averaged U_s falls
  -- below 10 % of its peak (R_C_s; shrinks with every refinement of the apex); rings: -1
  if s.inner == 0 then
    sim:compute("core", "core_radius", {mesh = "disc"})
    sim:compute("core_s", "core_radius", {mesh = "disc", criterion = "stretching"})
  end
  function s.core_radius(id)
    return s.inner == 0 and sim:value((id or "core") .. ".radius") or -1
  end
  -- relaxations: FIRE by default; -v minimizer=lbfgs for L-BFGS (frictionless scenes only:
  -- friction springs need FIRE's motion; each iteration moves a node by at most h / 4, so no
  -- step jumps through a contact; -v memory= correction pairs). With a refined core (h = 0.02,
  -- edge 1/16, core 1/64) L-BFGS reaches FIRE's equilibria (E_b_hat within 1e-4, the kiss
  -- one bisection step apart) in 15 times fewer iterations; on uniform meshes, whose apex is
  -- under-resolved, it lands on other equilibria within the tolerance (E_b_hat up to 0.8 %
  -- apart, the kiss 0.25 % lower at edge 1/16, 2 % at 1/32). -v integrator= is the same switch.
  -- -v minimizer=damped relaxes by damped dynamics instead: explicit Newmark (gamma = 1) with
  -- mass-proportional damping (-v damping=, per time unit) at its stable step, until the force
  -- is below ftol and the kinetic energy below ketol_rel * Y h^3 (the bending energy scale of
  -- the unit disc; default 1e-7).
  s.minimizer = slender.var("minimizer", slender.var("integrator", opts.minimizer or "fire"))
  if s.minimizer ~= "fire" and s.minimizer ~= "lbfgs" and s.minimizer ~= "damped" and
     s.minimizer ~= "newton" then
    error("minimizer must be fire, lbfgs, damped or newton, got " .. tostring(s.minimizer))
  end
  s.ketol = s.minimizer == "damped" and slender.var("ketol_rel", 1e-7) * s.young * s.h ^ 3 or nil
  if s.minimizer == "damped" then
    sim:integrator("newmark", {gamma = 1, damping = slender.var("damping", 5)})
  else
    sim:integrator("fire", {})
  end
  sim:dump("surface", "shell", {file = s.out .. "/surface.h5", every = 1000000000, mesh = "disc",
                                faces = s.contact and {"koiter.Ub", "koiter.Us", "contact/shell.contact"}
                                        or {"koiter.Ub", "koiter.Us"}})
  print(string.format("e-cone: h = %g, %d nodes, %d triangles, ftol = %.3g%s", s.h, s.nodes, s.tris,
                      s.ftol, s.ketol and string.format(", ketol = %.3g", s.ketol) or ""))

  -- wall times count from s.t0; a resumed ramp moves it back by the earlier runs' time
  s.t0 = slender.clock()
  -- grow to phi_e and relax to equilibrium; returns the FIRE steps
  s.steps_total = 0  -- FIRE steps of all relaxations, for element-steps/s
  local method = ({fire = "fire", lbfgs = "lbfgs", damped = "dynamics", newton = "newton"})[s.minimizer]
  local lbfgs = s.minimizer == "lbfgs" and
                -- memory 20: 20 % faster than 50 on the default ramp (docs/shells/README.md)
                {memory = slender.var("memory", 20), max_move = s.h / 4,
                 -- -v precondition=hessian: the factorised exact Hessian as L-BFGS's
                 -- initial inverse Hessian (docs/models.md §9.3)
                 precondition = slender.var("precondition", opts.precondition or "none"),
                 precondition_every = slender.var("precondition_every", 200)} or {}
  -- Newton keeps a factorisation while an iteration halves the largest force (modified
  -- Newton, docs/models.md §9.3; -v keep_factorization=0: plain Newton): 3.4x faster to
  -- phi_e = 2 than plain Newton before the kept pattern, the same Eb_hat to 1e-5
  local keep = s.minimizer == "newton" and slender.var("keep_factorization", 0.5) or nil
  function s.relax(phi)
    sim:modify("g", {phi_e = phi})
    local n = sim:minimize{ftol = s.ftol, max_steps = s.max_steps, method = method, ketol = s.ketol,
                           memory = lbfgs.memory, max_move = lbfgs.max_move,
                           precondition = lbfgs.precondition,
                           precondition_every = lbfgs.precondition_every,
                           keep_factorization = keep}
    s.steps_total = s.steps_total + n
    return n
  end
  -- a CSV log of equilibrium states; extra columns (e.g. the branch) go first; `append`
  -- continues the log of a resumed run
  function s.open_log(name, extra, append)
    s.extra = extra or {}
    local path = s.out .. "/" .. name
    local csv = assert(io.open(path, append and "a" or "w"))
    s.csv = csv
    if append then return end
    local head = {}
    for _, k in ipairs(s.extra) do head[#head + 1] = k end
    csv:write(table.concat(head, ",") .. (#head > 0 and "," or "") ..
              "phi_e,E_s,E_b,Eb_hat,area,wings,a2,a3,contacts,far_contacts,gamma,R_C,R_C_s,mid_gap,steps,wall_s\n")
  end
  function s.record(phi, steps, extra_values)
    local row = {}
    for _, v in ipairs(extra_values or {}) do row[#row + 1] = tostring(v) end
    for _, v in ipairs{phi, sim:value("koiter.stretch"), sim:value("koiter.bend"),
                       sim:value("koiter.Eb_hat"), sim:value("koiter.area"), sim:value("rim.n"),
                       sim:value("rim.a2"), sim:value("rim.a3"), s.cv("contacts"),
                       s.cv("far_contacts"), s.cv("gamma"), s.core_radius(),
                       s.core_radius("core_s"), sim:value("gap.distance"), steps,
                       slender.clock() - s.t0} do
      row[#row + 1] = string.format("%.8g", v)
    end
    s.csv:write(table.concat(row, ",") .. "\n")
    s.csv:flush()
    print(string.format("%sphi_e %.4f  Eb_hat %.4f  E_s/E_b %.3f  wings %d  contacts %d  gamma %.3f  R_C %.4f  R_C_s %.4f  steps %d",
                        extra_values and (table.concat(extra_values, " ") .. "  ") or "", phi,
                        sim:value("koiter.Eb_hat"),
                        sim:value("koiter.stretch") / sim:value("koiter.bend"), sim:value("rim.n"),
                        s.cv("contacts"), s.cv("gamma"), s.core_radius(),
                        s.core_radius("core_s"), steps))
  end
  return s
end

return M
