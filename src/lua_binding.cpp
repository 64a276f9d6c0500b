#include "lua_binding.hpp"

#include <csignal>

#include <lua.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "continuation.hpp"
#include "file_check.hpp"
#include "registry.hpp"
#include "rod_frames.hpp"
#include "scene_build.hpp"
#include "simulation.hpp"
#include "stiffness.hpp"

namespace slender {

namespace {

const char* kSimMeta = "slender.Simulation";

// The one process-wide datum: the signal that asked the deck to stop (SIGINT, SIGTERM). A
// signal belongs to the process, not to a simulation; every simulation of the deck watches
// this flag and stops cleanly after its step. A second signal ends the process at once.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  if (g_stop_signal != 0) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_stop_signal = sig;
}

// Per-deck context kept in the Lua state's extra space: no globals.
struct DeckContext {
  DeckOptions opt;
  std::set<std::string> vars_read;  // -v names the deck asked for (slender.var)
  bool instability = false;
  bool interrupted = false;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
};
DeckContext*& context(lua_State* L) {
  return *static_cast<DeckContext**>(lua_getextraspace(L));
}

// An error whose message already names the deck line (e.g. from a callback).
struct LocatedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SimBox {
  Simulation* sim;
};

Simulation& sim_arg(lua_State* L, int idx = 1) {
  auto* box = static_cast<SimBox*>(luaL_testudata(L, idx, kSimMeta));
  if (!box || !box->sim)
    throw InputError("expected a simulation (use sim:method(...), not sim.method(...))");
  return *box->sim;
}

std::string str_arg(lua_State* L, int idx, const char* what) {
  if (lua_type(L, idx) != LUA_TSTRING)
    throw InputError(std::string("expected a string for ") + what);
  return lua_tostring(L, idx);
}
double num_arg(lua_State* L, int idx, const char* what) {
  if (lua_type(L, idx) != LUA_TNUMBER)
    throw InputError(std::string("expected a number for ") + what);
  return lua_tonumber(L, idx);
}

// A node index argument: an integer (10.5 would silently read node 10).
long index_arg(lua_State* L, int idx, const char* what) {
  const double v = num_arg(L, idx, what);
  if (!(std::abs(v) < 9.0e15) || v != std::floor(v))
    throw InputError(std::string(what) + " must be an integer, got " + std::to_string(v));
  return static_cast<long>(v);
}

// Lua value -> raw parameter value (numbers, booleans, strings, flat lists).
Value to_value(lua_State* L, int idx, const std::string& key) {
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
      return lua_tonumber(L, idx);
    case LUA_TBOOLEAN:
      return static_cast<bool>(lua_toboolean(L, idx));
    case LUA_TSTRING:
      return std::string(lua_tostring(L, idx));
    case LUA_TTABLE: {
      idx = lua_absindex(L, idx);
      const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
      std::vector<double> nums;
      std::vector<std::string> strs;
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, idx, i);
        if (lua_type(L, -1) == LUA_TNUMBER)
          nums.push_back(lua_tonumber(L, -1));
        else if (lua_type(L, -1) == LUA_TSTRING)
          strs.push_back(lua_tostring(L, -1));
        else {
          lua_pop(L, 1);
          throw InputError("key '" + key + "': lists may hold only numbers or only strings");
        }
        lua_pop(L, 1);
      }
      if (!nums.empty() && !strs.empty())
        throw InputError("key '" + key + "': a list mixes numbers and strings");
      if (!nums.empty()) return nums;
      return strs;
    }
    case LUA_TFUNCTION:
      return DeckFunction{};  // kept by the caller (a callback, a growth law)
    default:
      throw InputError("key '" + key + "' has a " + luaL_typename(L, idx) +
                       " value, which no style parameter accepts");
  }
}

// A Lua table of named parameters -> RawParams. Keys listed in `skip` are left
// for the caller (e.g. callbacks).
RawParams to_raw(lua_State* L, int idx, const std::vector<std::string>& skip = {}) {
  RawParams raw;
  if (lua_isnoneornil(L, idx)) return raw;
  if (!lua_istable(L, idx)) throw InputError("expected a table of parameters {key = value, ...}");
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      lua_pop(L, 2);
      throw InputError("parameter tables take names as keys: {key = value}");
    }
    std::string key = lua_tostring(L, -2);
    bool skipped = false;
    for (auto& s : skip) skipped = skipped || s == key;
    if (!skipped) {
      try {
        raw[key] = to_value(L, -1, key);
      } catch (...) {
        lua_pop(L, 2);
        throw;
      }
    }
    lua_pop(L, 1);
  }
  return raw;
}

// ------------------------------------------------------------ commands

ParamSpec simulation_spec() {
  ParamSpec s("command", "simulation", "slender.simulation{...}: a new, empty scene");
  s.integer("dimension", "2 or 3").def(3.0).min(2).max(3);
  s.integer("seed", "seed of the scene's random stream").def(1.0).min(0);
  s.boolean("quiet", "no run summaries or thermo on the console").def(false);
  return s;
}

ParamSpec thermo_spec() {
  ParamSpec s("command", "thermo", "sim:thermo{...}: console and CSV output of chosen columns");
  s.integer("every", "steps between lines (0: off)").def(0.0).min(0);
  s.real("interval",
         "time between lines, instead of every (the same output at any dt and under an "
         "adaptive step)")
      .positive();
  s.add("columns", ParamType::StringList,
        "step, time, dt, nodes, ke, pe, etotal, fmax, energy.<category>, <id>.<key>")
      .def(std::vector<std::string>{"step", "time", "ke", "pe", "etotal"});
  s.string("file", "CSV file (same columns)");
  s.boolean("append", "append to an existing CSV (a restarted run) instead of replacing it")
      .def(false);
  s.boolean("console", "print to the console").def(true);
  s.real("progress", "seconds between progress/ETA lines").def(5.0).positive();
  return s;
}

ParamSpec guard_spec() {
  ParamSpec s("command", "guard", "sim:guard{...}: the instability guard");
  s.integer("every", "steps between checks (outputs are always checked)").def(10.0).min(1);
  s.real("max_step_fraction", "max |v| dt over the shortest rest length").def(0.5).positive();
  s.real("ke_factor", "max kinetic energy over the largest energy seen").def(100.0).positive();
  s.real("max_strain", "max |edge length / rest length - 1| (a torn or crushed wire)")
      .def(0.5)
      .positive();
  s.string("last_good_file", "where the last good state is written")
      .def(std::string("slender_last_good.h5"));
  return s;
}

ParamSpec run_spec() {
  ParamSpec s("command", "run", "sim:run{...} or sim:run(steps)");
  s.integer("steps", "number of steps").required().min(0);
  s.integer("every", "steps between callback calls").def(0.0).min(0);
  s.add("callback", ParamType::Function,
        "function(sim) called every `every` steps; return true to stop");
  return s;
}

ParamSpec minimize_spec() {
  ParamSpec s(
      "command", "minimize",
      "sim:minimize{...}: relaxation to static equilibrium (FIRE, or L-BFGS or Newton on the node "
      "positions); returns the iterations and whether ftol was reached");
  s.real("ftol",
         "stop when the largest nodal force (and rod-frame generalised force) is below this")
      .def(1e-8)
      .positive();
  s.integer("max_steps", "give up after this many steps").def(1e6).min(1);
  s.string("method",
           "\"fire\" (damped dynamics; nodes and rod frames), \"lbfgs\" (quasi-Newton on the "
           "energy; node positions only, forces must derive from the energy, friction springs "
           "hold their force), \"newton\" (Newton-Raphson with the exact Hessians of the "
           "styles, docs/models.md §9.3; node positions only, every force style must have a "
           "Hessian) or \"dynamics\" (the scene's own integrator and damping, e.g. "
           "newmark with mass-proportional damping; needs ketol)")
      .def(std::string("fire"));
  s.add("ketol", ParamType::RealOrAuto,
        "also require the kinetic energy to be at most this (needed by \"dynamics\"); "
        "\"auto\": not checked")
      .def(std::string("auto"))
      .min(0);
  s.integer("memory", "lbfgs: number of correction pairs kept").def(10.0).min(1);
  s.add(
       "max_move", ParamType::RealOrAuto,
       "lbfgs, newton: largest node displacement per iteration (keep it below the contact distance "
       "where there is contact); \"auto\": unlimited")
      .def(std::string("auto"))
      .positive();
  s.string("precondition",
           "lbfgs: \"hessian\" takes the factorised exact Hessian (shifted until positive "
           "definite) as the initial inverse Hessian, for ill-conditioned scenes such as thin "
           "shells; \"none\": a scalar (integrator lbfgs's parameter of the same name)")
      .def(std::string("none"))
      .choices({"none", "hessian"});
  s.integer("precondition_every",
            "lbfgs with precondition = \"hessian\": iterations between refactorisations (0: at "
            "the start and after a restart)")
      .def(200.0)
      .min(0);
  s.real("keep_factorization",
         "newton: keep the last factorisation while an iteration cuts the largest force by at "
         "least this factor (modified Newton: a solve instead of an assembly and a "
         "factorisation) and start each factorisation from the last Levenberg shift; 0: plain "
         "Newton (integrator newton's parameter of the same name)")
      .def(0.0)
      .min(0.0)
      .max(1.0, true);
  return s;
}

ParamSpec stiffness_spec() {
  ParamSpec s(
      "command", "lowest_stiffness",
      "sim:lowest_stiffness{...}: lowest eigenvalue of the stiffness matrix (Hessian of "
      "the energy) at the current state, by central differences of the forces; negative: "
      "the equilibrium is unstable; free modes (a rigid motion, a free rod end's twist) sit "
      "at zero within the difference error. Returns it and the degrees of freedom. "
      "Friction springs advance with each force evaluation: use it without friction");
  s.real("eps", "finite-difference step (length; frames: quaternion units)").def(1e-6).positive();
  return s;
}

ParamSpec continuation_spec() {
  ParamSpec s("command", "continuation",
              "sim:continuation{...}: follows static equilibria as the load of a fix is scaled "
              "by lambda, through limit points (pseudo-arc-length, Newton with the exact "
              "Hessians, docs/models.md §9.4), and reports where the count of unstable "
              "directions changes (limit and bifurcation points); returns the points taken and "
              "the last lambda");
  s.string("load",
           "id of the style whose load lambda scales (fixes force/constant, moment2d, "
           "prescribe; shell koiter: load, line_load, line_moment, pressure), or growth econe, "
           "whose excess angle phi_e is lambda")
      .required();
  s.real("lambda0",
         "load factor at the start (the state must be, or Newton must reach, an "
         "equilibrium there)")
      .def(0.0);
  s.real("lambda_min", "stop below this load factor").def(-1e300);
  s.real("lambda_max", "stop above this load factor").def(1e300);
  s.real("ds",
         "first arc-length step (docs/models.md §9.4: displacement, with lambda weighed "
         "by the displacement a unit of it causes at the start)")
      .def(0.05)
      .positive();
  s.real("ds_max", "largest arc-length step").def(0.5).positive();
  s.real("ds_min", "smallest arc-length step before giving up").def(1e-8).positive();
  s.integer("points", "converged points to take at most").def(100.0).min(1);
  s.real("ftol", "largest nodal force at a converged point").def(1e-8).positive();
  s.integer("max_iterations", "corrector iterations before the step is halved")
      .def(25.0)
      .min(1)
      .max(10000);
  s.boolean("switch_branch",
            "at the first bifurcation point, leave the path onto the bifurcated branch (along "
            "the null vector of the stiffness matrix, docs/models.md §9.4)")
      .def(false);
  s.add("callback", ParamType::Function,
        "function(sim, point) called at the start and at every converged point, point = "
        "{index, lambda, negative_pivots, iterations, ds, event, critical_lambda} (event: \"limit "
        "point\", \"bifurcation point\" or nil, crossed since the last point; critical_lambda: "
        "where, bisected on the arc length); return true to stop");
  return s;
}

// The command declarations join the catalog, so `slender --help wire` and
// docs/styles.md describe them from the same declarations that validate decks.
[[maybe_unused]] const bool commands_registered = [] {
  for (auto* spec : {&simulation_spec, &wire_spec, &group_spec, &thermo_spec, &guard_spec,
                     &run_spec, &minimize_spec, &continuation_spec, &stiffness_spec, &mesh_spec}) {
    ParamSpec s = (*spec)();
    Catalog::entries().push_back(CatalogEntry{"command", s.name, *spec});
  }
  return true;
}();

// ------------------------------------------------------------ methods

// -t N, else OMP_NUM_THREADS (a positive integer), else 1.
int deck_threads(const DeckOptions& opt) {
  if (opt.threads > 0) return opt.threads;
  if (const char* env = std::getenv("OMP_NUM_THREADS")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && n >= 1)
      return static_cast<int>(std::min<long>(n, kMaxThreads));
  }
  return 1;
}

int l_simulation(lua_State* L) {
  auto p = simulation_spec().validate(to_raw(L, 1));
  auto sim = std::make_unique<Simulation>(static_cast<int>(p.integer("dimension")),
                                          static_cast<std::uint64_t>(p.integer("seed")));
  sim->verbose = !(p.boolean("quiet") || context(L)->opt.quiet);
  sim->set_threads(deck_threads(context(L)->opt));
  if (const char* env = std::getenv("SLENDER_THREADS_MIN_NODES")) {
    char* end = nullptr;
    const long n = std::strtol(env, &end, 10);
    if (end == env || *end != '\0' || n < 0)
      throw InputError(std::string("SLENDER_THREADS_MIN_NODES must be a count >= 0, got '") + env +
                       "'");
    sim->set_threads_min_nodes(static_cast<std::size_t>(n));
  }
  if (context(L)->opt.catch_signals) sim->watch_interrupt(&g_stop_signal);
  auto* box = static_cast<SimBox*>(lua_newuserdatauv(L, sizeof(SimBox), 1));
  box->sim = sim.release();
  luaL_setmetatable(L, kSimMeta);
  return 1;
}

int l_gc(lua_State* L) {
  auto* box = static_cast<SimBox*>(luaL_testudata(L, 1, kSimMeta));
  if (box && box->sim) {
    if (!context(L)->opt.inventory.empty()) {
      std::ofstream inv(context(L)->opt.inventory, std::ios::app);
      inv << box->sim->inventory_json() << "\n";
    }
    delete box->sim;
    box->sim = nullptr;
  }
  return 0;
}

std::vector<Vec3> read_points(lua_State* L, int tbl) {
  std::vector<Vec3> pts;
  lua_getfield(L, tbl, "points");
  if (lua_istable(L, -1)) {
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, i);
      Vec3 p = Vec3::Zero();
      bool ok = lua_istable(L, -1);
      if (ok) {
        for (int c = 0; c < 3; ++c) {
          lua_rawgeti(L, -1, c + 1);
          if (lua_type(L, -1) == LUA_TNUMBER)
            p[c] = lua_tonumber(L, -1);
          else if (c < 2)
            ok = false;
          lua_pop(L, 1);
        }
      }
      lua_pop(L, 1);
      if (!ok) {
        lua_pop(L, 1);
        throw InputError("wire: points must be a list of {x, y[, z]}");
      }
      pts.push_back(p);
    }
  }
  lua_pop(L, 1);
  return pts;
}

int l_wire(lua_State* L) {
  Simulation& sim = sim_arg(L);
  if (!lua_istable(L, 2)) throw InputError("wire: expected a table {name = ..., nodes = ...}");
  std::vector<Vec3> pts = read_points(L, 2);
  Chain& c = add_wire(sim, to_raw(L, 2, {"points"}), std::move(pts));
  lua_pushinteger(L, c.n_nodes());
  return 1;
}

int l_group(lua_State* L) {
  Simulation& sim = sim_arg(L);
  std::string name = str_arg(L, 2, "the group name");
  lua_pushinteger(L, static_cast<lua_Integer>(add_group(sim, name, to_raw(L, 3))));
  return 1;
}

int l_region(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.add_region(str_arg(L, 2, "the region id"), str_arg(L, 3, "the region style"), to_raw(L, 4));
  return 0;
}
int l_bond(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto& b = sim.add_bond(str_arg(L, 2, "the bond style"), to_raw(L, 3));
  lua_pushstring(L, b.id().c_str());
  return 1;
}
int l_pair(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto& b = sim.add_pair(str_arg(L, 2, "the pair style"), to_raw(L, 3));
  lua_pushstring(L, b.id().c_str());
  return 1;
}
int l_mesh(lua_State* L) {
  Simulation& sim = sim_arg(L);
  const auto [nodes, triangles] = add_mesh(sim, to_raw(L, 2));
  lua_pushinteger(L, nodes);
  lua_pushinteger(L, triangles);
  return 2;
}
int l_shell(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto& b = sim.add_shell(str_arg(L, 2, "the shell style"), to_raw(L, 3));
  lua_pushstring(L, b.id().c_str());
  return 1;
}
// Growth from a deck function fn(x, y, z, t) of the reference position and time that
// returns a scalar g (isotropic), {gxx, gxy, gyx, gyy} (in-plane, world xy) or nine
// numbers (row by row).
Eigen::Matrix3d call_growth_function(lua_State* L, int ref, const Vec3& X, double t) {
  lua_rawgeti(L, LUA_REGISTRYINDEX, ref);
  lua_pushnumber(L, X.x());
  lua_pushnumber(L, X.y());
  lua_pushnumber(L, X.z());
  lua_pushnumber(L, t);
  if (lua_pcall(L, 4, 1, 0) != LUA_OK) {
    std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error";
    lua_pop(L, 1);
    throw InputError("growth function: " + msg);
  }
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  if (lua_type(L, -1) == LUA_TNUMBER) {
    G *= lua_tonumber(L, -1);
  } else if (lua_istable(L, -1)) {
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    if (n != 4 && n != 9) {
      lua_pop(L, 1);
      throw InputError("growth function: return a number, 4 or 9 numbers");
    }
    for (lua_Integer k = 1; k <= n; ++k) {
      lua_rawgeti(L, -1, k);
      const double v = lua_tonumber(L, -1);
      lua_pop(L, 1);
      if (n == 4)
        G(static_cast<int>((k - 1) / 2), static_cast<int>((k - 1) % 2)) = v;
      else
        G(static_cast<int>((k - 1) / 3), static_cast<int>((k - 1) % 3)) = v;
    }
  } else {
    lua_pop(L, 1);
    throw InputError("growth function: return a number, 4 or 9 numbers");
  }
  lua_pop(L, 1);
  return G;
}
int l_growth(lua_State* L) {
  Simulation& sim = sim_arg(L);
  const std::string id = str_arg(L, 2, "the growth id"), style = str_arg(L, 3, "the growth style");
  int ref = LUA_NOREF;
  if (lua_istable(L, 4)) {
    lua_getfield(L, 4, "fn");
    if (lua_isfunction(L, -1))
      ref = luaL_ref(L, LUA_REGISTRYINDEX);
    else
      lua_pop(L, 1);
  }
  auto& g = sim.add_growth(id, style, to_raw(L, 4));
  if (g.wants_function()) {
    if (ref == LUA_NOREF)
      throw InputError("growth '" + style + "' needs fn = function(x, y, z, t)");
    g.set_function(
        [L, ref](const Vec3& X, double t) { return call_growth_function(L, ref, X, t); });
  } else if (ref != LUA_NOREF) {
    throw InputError("growth '" + style + "' takes no fn");
  }
  return 0;
}
int l_fix(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.add_fix(str_arg(L, 2, "the fix id"), str_arg(L, 3, "the fix style"), to_raw(L, 4));
  return 0;
}
int l_unfix(lua_State* L) {
  sim_arg(L).remove_fix(str_arg(L, 2, "the fix id"));
  return 0;
}
int l_compute(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.add_compute(str_arg(L, 2, "the compute id"), str_arg(L, 3, "the compute style"),
                  to_raw(L, 4));
  return 0;
}
int l_dump(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.add_dump(str_arg(L, 2, "the dump id"), str_arg(L, 3, "the dump style"), to_raw(L, 4));
  return 0;
}
int l_integrator(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.set_integrator(str_arg(L, 2, "the integrator style"), to_raw(L, 3));
  return 0;
}
int l_modify(lua_State* L) {
  Simulation& sim = sim_arg(L);
  sim.modify_style(str_arg(L, 2, "the style id"), to_raw(L, 3));
  return 0;
}
int l_thermo(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto p = thermo_spec().validate(to_raw(L, 2));
  sim.thermo.every = p.integer("every");
  sim.thermo.interval = p.has("interval") ? p.real("interval") : 0.0;
  if (sim.thermo.every > 0 && sim.thermo.interval > 0)
    throw InputError("thermo: give every (steps) or interval (time), not both");
  sim.thermo.columns = p.strings("columns");
  sim.thermo.file = p.has("file") ? p.str("file") : "";
  sim.thermo.append = p.boolean("append");
  sim.thermo.console = p.boolean("console");
  sim.thermo.progress_seconds = p.real("progress");
  for (auto& c : sim.thermo.columns) {
    // validate names now, so a typo stops the deck at this line
    auto dot = c.find('.');
    bool ok = false;
    for (auto& b : Simulation::builtin_columns()) ok = ok || c == b;
    if (!ok && dot != std::string::npos) {
      std::string id = c.substr(0, dot);
      Style* s = sim.find_style(id);
      ok = id == "energy" || (s && [&] {
             for (auto& k : s->value_keys())
               if (k == c.substr(dot + 1)) return true;
             return false;
           }());
    }
    if (!ok) {
      std::string known;
      if (dot != std::string::npos)
        if (Style* s = sim.find_style(c.substr(0, dot))) {
          for (auto& k : s->value_keys()) known += (known.empty() ? "" : ", ") + k;
          known = "; '" + s->id() + "' (" + s->family_name() + " " + s->style_name() + ") offers " +
                  (known.empty() ? std::string("no values") : known);
        }
      if (known.empty()) {
        for (auto& b : Simulation::builtin_columns()) known += (known.empty() ? "" : ", ") + b;
        known = "; built in: " + known + "; or <id>.<key> of a style, energy.<category>";
      }
      throw InputError("thermo: unknown column '" + c + "'" + known);
    }
  }
  return 0;
}
int l_guard(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto p = guard_spec().validate(to_raw(L, 2));
  sim.guard.every = p.integer("every");
  sim.guard.max_step_fraction = p.real("max_step_fraction");
  sim.guard.ke_factor = p.real("ke_factor");
  sim.guard.max_strain = p.real("max_strain");
  // written only when the guard fires: a path that cannot take it is said now, at this line
  require_writable("guard: last_good_file", p.str("last_good_file"));
  sim.guard.last_good_file = p.str("last_good_file");
  return 0;
}

int l_run(lua_State* L) {
  Simulation& sim = sim_arg(L);
  RunOptions opt;
  int cb_ref = LUA_NOREF;
  if (lua_type(L, 2) == LUA_TNUMBER) {
    // sim:run(n) is sim:run{steps = n}, with the same checks (an integer, >= 0, at most
    // 2^53, so that 2^63 is not refused as "negative" after an overflow)
    lua_createtable(L, 0, 1);
    lua_pushvalue(L, 2);
    lua_setfield(L, -2, "steps");
    lua_replace(L, 2);
  }
  {
    auto p = run_spec().validate(to_raw(L, 2));
    opt.steps = p.integer("steps");
    opt.every = p.integer("every");
    lua_getfield(L, 2, "callback");
    if (lua_isfunction(L, -1)) {
      cb_ref = luaL_ref(L, LUA_REGISTRYINDEX);
      if (opt.every <= 0) opt.every = 1;
    } else {
      bool bad = !lua_isnil(L, -1);
      lua_pop(L, 1);
      if (bad) throw InputError("run: callback must be a function");
    }
  }
  if (cb_ref != LUA_NOREF) {
    opt.callback = [L, cb_ref](Simulation&) {
      lua_rawgeti(L, LUA_REGISTRYINDEX, cb_ref);
      lua_pushvalue(L, 1);  // the simulation userdata
      if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
        std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in callback";
        lua_pop(L, 1);
        throw LocatedError(msg);
      }
      bool stop = lua_toboolean(L, -1);
      lua_pop(L, 1);
      return stop;
    };
  }
  struct Unref {
    lua_State* L;
    int ref;
    ~Unref() { luaL_unref(L, LUA_REGISTRYINDEX, ref); }
  } unref{L, cb_ref};
  sim.run(opt);
  lua_pushinteger(L, sim.step);
  return 1;
}

int l_minimize(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto p = minimize_spec().validate(to_raw(L, 2));
  const std::string method = p.str("method");
  RawParams lbfgs;
  if (method == "lbfgs") {
    lbfgs["memory"] = static_cast<double>(p.integer("memory"));
    lbfgs["precondition"] = p.str("precondition");
    lbfgs["precondition_every"] = static_cast<double>(p.integer("precondition_every"));
  }
  if ((method == "lbfgs" || method == "newton") && !p.is_auto("max_move"))
    lbfgs["max_move"] = p.real("max_move");
  if (method == "newton") lbfgs["keep_factorization"] = p.real("keep_factorization");
  const double ketol =
      p.is_auto("ketol") ? std::numeric_limits<double>::infinity() : p.real("ketol");
  long n = sim.minimize(p.real("ftol"), p.integer("max_steps"), method, lbfgs, ketol);
  lua_pushinteger(L, n);
  // velocities are zeroed after the relaxation: the kinetic criterion held if it stopped early
  lua_pushboolean(
      L, sim.max_force() < p.real("ftol") && (!std::isfinite(ketol) || n < p.integer("max_steps")));
  return 2;
}

int l_continuation(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto p = continuation_spec().validate(to_raw(L, 2));
  ContinuationOptions opt;
  opt.load = p.str("load");
  opt.lambda0 = p.real("lambda0");
  opt.lambda_min = p.real("lambda_min");
  opt.lambda_max = p.real("lambda_max");
  opt.ds = p.real("ds");
  opt.ds_max = p.real("ds_max");
  opt.ds_min = p.real("ds_min");
  opt.points = p.integer("points");
  opt.ftol = p.real("ftol");
  opt.max_iterations = static_cast<int>(p.integer("max_iterations"));
  opt.switch_branch = p.boolean("switch_branch");
  int cb_ref = LUA_NOREF;
  lua_getfield(L, 2, "callback");
  if (lua_isfunction(L, -1)) {
    cb_ref = luaL_ref(L, LUA_REGISTRYINDEX);
  } else {
    const bool bad = !lua_isnil(L, -1);
    lua_pop(L, 1);
    if (bad) throw InputError("continuation: callback must be a function");
  }
  struct Unref {
    lua_State* L;
    int ref;
    ~Unref() { luaL_unref(L, LUA_REGISTRYINDEX, ref); }
  } unref{L, cb_ref};
  if (cb_ref != LUA_NOREF)
    opt.callback = [L, cb_ref](Simulation&, const ContinuationPoint& pt) {
      lua_rawgeti(L, LUA_REGISTRYINDEX, cb_ref);
      lua_pushvalue(L, 1);  // the simulation userdata
      lua_createtable(L, 0, 6);
      lua_pushinteger(L, pt.index);
      lua_setfield(L, -2, "index");
      lua_pushnumber(L, pt.lambda);
      lua_setfield(L, -2, "lambda");
      lua_pushinteger(L, pt.negative_pivots);
      lua_setfield(L, -2, "negative_pivots");
      lua_pushinteger(L, pt.iterations);
      lua_setfield(L, -2, "iterations");
      lua_pushnumber(L, pt.ds);
      lua_setfield(L, -2, "ds");
      if (!pt.event.empty()) {
        lua_pushstring(L, pt.event.c_str());
        lua_setfield(L, -2, "event");
        lua_pushnumber(L, pt.critical_lambda);
        lua_setfield(L, -2, "critical_lambda");
      }
      if (lua_pcall(L, 2, 1, 0) != LUA_OK) {
        std::string msg = lua_tostring(L, -1) ? lua_tostring(L, -1) : "error in callback";
        lua_pop(L, 1);
        throw LocatedError(msg);
      }
      const bool stop = lua_toboolean(L, -1);
      lua_pop(L, 1);
      return stop;
    };
  const ContinuationResult r = continuation(sim, opt);
  lua_pushinteger(L, r.points);
  lua_pushnumber(L, r.lambda);
  return 2;
}

int l_lowest_stiffness(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto p = stiffness_spec().validate(to_raw(L, 2));
  const StiffnessResult r = lowest_stiffness(sim, p.real("eps"));
  lua_pushnumber(L, r.lowest);
  lua_pushinteger(L, r.dofs);
  return 2;
}

int l_write_dump(lua_State* L) {
  Simulation& sim = sim_arg(L);
  const std::string id = str_arg(L, 2, "the dump id");
  auto* d = dynamic_cast<DumpStyle*>(sim.find_style(id));
  if (!d) throw InputError("write_dump: no dump with id '" + id + "'");
  if (!sim.forces_valid) sim.compute_forces();
  d->write(sim);
  return 0;
}
int l_value(lua_State* L) {
  Simulation& sim = sim_arg(L);
  lua_pushnumber(L, sim.column(str_arg(L, 2, "the column name")));
  return 1;
}

int push_vec(lua_State* L, const Vec3& v, int dim) {
  for (int c = 0; c < dim; ++c) lua_pushnumber(L, v[c]);
  return dim;
}
int l_position(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "position");
  return push_vec(L, sim.nodes().x[i], sim.dimension());
}
int l_velocity(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "velocity");
  return push_vec(L, sim.nodes().v[i], sim.dimension());
}
int l_force(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "force");
  return push_vec(L, sim.nodes().f[i], sim.dimension());
}
// sim:frame(i): the rod frame of the edge from node i, {q = {w, x, y, z}, d1 = {...},
// d2 = {...}, d3 = {...}} (src/rod_frames.hpp)
int l_frame(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "frame");
  const Vec4 q = rod_frame(sim, i);
  auto list = [&](const char* key, std::initializer_list<double> xs) {
    lua_createtable(L, static_cast<int>(xs.size()), 0);
    int k = 1;
    for (double x : xs) {
      lua_pushnumber(L, x);
      lua_rawseti(L, -2, k++);
    }
    lua_setfield(L, -2, key);
  };
  lua_createtable(L, 0, 4);
  list("q", {q[0], q[1], q[2], q[3]});
  const Vec3 a = qrod::d1(q), b = qrod::d2(q), c = qrod::d3(q);
  list("d1", {a.x(), a.y(), a.z()});
  list("d2", {b.x(), b.y(), b.z()});
  list("d3", {c.x(), c.y(), c.z()});
  return 1;
}
// sim:set_frame(i, {q = {w, x, y, z}}) or (i, {d1 = {...}, d3 = {...}})
int l_set_frame(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "set_frame");
  luaL_checktype(L, 3, LUA_TTABLE);
  auto field = [&](const char* key, std::size_t n) -> std::optional<Eigen::VectorXd> {
    lua_getfield(L, 3, key);
    if (lua_isnil(L, -1)) {
      lua_pop(L, 1);
      return std::nullopt;
    }
    Value v = to_value(L, -1, key);
    lua_pop(L, 1);
    auto* d = std::get_if<std::vector<double>>(&v);
    if (!d || d->size() != n)
      throw InputError(std::string("set_frame: '") + key + "' must be a list of " +
                       std::to_string(n) + " numbers");
    return Eigen::Map<const Eigen::VectorXd>(d->data(), static_cast<long>(n));
  };
  const auto q = field("q", 4);
  const auto d1 = field("d1", 3), d3 = field("d3", 3);
  if (q && (d1 || d3)) throw InputError("set_frame: give either q or d1 and d3, not both");
  if (q) {
    set_rod_frame(sim, i, Vec4((*q)[0], (*q)[1], (*q)[2], (*q)[3]));
  } else if (d1 && d3) {
    set_rod_frame(sim, i, frame_from_directors(Vec3(*d1), Vec3(*d3)));
  } else {
    throw InputError("set_frame: give {q = {w, x, y, z}} or {d1 = {x, y, z}, d3 = {x, y, z}}");
  }
  return 0;
}
int l_set_position(lua_State* L) {
  Simulation& sim = sim_arg(L);
  int i = node_index(index_arg(L, 2, "the node index"), sim.nodes().size(), "set_position");
  Value v = to_value(L, 3, "position");
  auto* d = std::get_if<std::vector<double>>(&v);
  if (!d || d->size() < 2 || d->size() > 3) throw InputError("set_position: expected {x, y[, z]}");
  for (double x : *d)
    if (!std::isfinite(x))
      throw InputError("set_position: node " + std::to_string(i + 1) +
                       " would get a non-finite coordinate (" + std::to_string(x) + ")");
  if (sim.dimension() == 2 && d->size() == 3 && (*d)[2] != 0.0)
    throw InputError("set_position: node " + std::to_string(i + 1) +
                     " would get z = " + std::to_string((*d)[2]) +
                     " in a 2D scene (dimension = 2), whose nodes move in the xy plane: give {x, "
                     "y}");
  for (size_t c = 0; c < d->size(); ++c) sim.nodes().x[i][static_cast<long>(c)] = (*d)[c];
  sim.forces_valid = false;
  ++sim.state_epoch;
  return 0;
}
int l_chain_node(lua_State* L) {
  Simulation& sim = sim_arg(L);
  std::string name = str_arg(L, 2, "the chain name");
  Chain* c = sim.topology().find(name);
  if (!c) throw InputError("unknown chain '" + name + "'");
  int k = node_index(index_arg(L, 3, "the index along the chain"), c->nodes.size(), name);
  lua_pushinteger(L, c->nodes[k] + 1);
  return 1;
}
int l_nnodes(lua_State* L) {
  lua_pushinteger(L, static_cast<lua_Integer>(sim_arg(L).nodes().n_owned()));
  return 1;
}
int l_step(lua_State* L) {
  lua_pushinteger(L, sim_arg(L).step);
  return 1;
}
int l_time(lua_State* L) {
  lua_pushnumber(L, sim_arg(L).time);
  return 1;
}
int l_dt(lua_State* L) {
  lua_pushnumber(L, sim_arg(L).dt);
  return 1;
}
int l_suggest_dt(lua_State* L) {
  Simulation& sim = sim_arg(L);
  double safety = lua_isnoneornil(L, 2) ? 1.0 : num_arg(L, 2, "the safety factor");
  lua_pushnumber(L, sim.suggest_dt(safety));
  return 1;
}
int l_properties(lua_State* L) {
  Simulation& sim = sim_arg(L);
  auto names = sim.nodes().property_names();
  lua_createtable(L, static_cast<int>(names.size()), 0);
  for (size_t i = 0; i < names.size(); ++i) {
    lua_pushstring(L, names[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}
int l_write_checkpoint(lua_State* L) {
  sim_arg(L).write_checkpoint(str_arg(L, 2, "the checkpoint file"));
  return 0;
}
int l_read_checkpoint(lua_State* L) {
  sim_arg(L).read_checkpoint(str_arg(L, 2, "the checkpoint file"));
  return 0;
}

int l_var(lua_State* L) {
  std::string name = str_arg(L, 1, "the variable name");
  context(L)->vars_read.insert(name);
  auto& vars = context(L)->opt.vars;
  auto it = vars.find(name);
  if (it == vars.end()) {
    lua_settop(L, 2);
    return 1;  // the default (nil if none)
  }
  // numbers arrive as numbers; "true"/"false" as booleans; the rest as strings
  if (lua_stringtonumber(L, it->second.c_str()) == 0) {
    if (it->second == "true" || it->second == "false")
      lua_pushboolean(L, it->second == "true");
    else
      lua_pushstring(L, it->second.c_str());
  }
  return 1;
}
int l_clock(lua_State* L) {
  auto dt = std::chrono::steady_clock::now() - context(L)->t0;
  lua_pushnumber(L, std::chrono::duration<double>(dt).count());
  return 1;
}
// slender.interrupted(): true once SIGINT or SIGTERM stopped a run, so that a deck that
// catches the run's error (pcall) can tell a stop it should report as cut short from an
// instability or a mistake.
int l_interrupted(lua_State* L) {
  lua_pushboolean(L, context(L)->interrupted);
  return 1;
}
// slender.result{key = value, ...}: one machine-readable line for sweep scripts.
int l_result(lua_State* L) {
  if (!lua_istable(L, 1)) throw InputError("result: expected a table {key = value}");
  std::map<std::string, std::string> kv;
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      std::string v;
      if (lua_type(L, -1) == LUA_TNUMBER) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.10g", lua_tonumber(L, -1));
        v = buf;
      } else {
        v = luaL_tolstring(L, -1, nullptr);
        lua_pop(L, 1);
      }
      kv[lua_tostring(L, -2)] = v;
    }
    lua_pop(L, 1);
  }
  std::string line = "RESULT";
  for (auto& [k, v] : kv) line += " " + k + "=" + v;
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
  return 0;
}
int l_styles(lua_State* L) {
  std::string fam = lua_isnoneornil(L, 1) ? "" : str_arg(L, 1, "the family");
  lua_newtable(L);
  lua_Integer k = 0;
  for (auto& e : Catalog::entries()) {
    if (!fam.empty() && e.family != fam) continue;
    lua_pushstring(L, (e.family + "/" + e.name).c_str());
    lua_rawseti(L, -2, ++k);
  }
  return 1;
}

// Runs F; C++ exceptions become Lua errors that name the deck line. The Lua
// error is raised only after every C++ object of F is destroyed.
template <int (*F)(lua_State*)>
int guarded(lua_State* L) {
  bool failed = false;
  try {
    return F(L);
  } catch (const LocatedError& e) {
    lua_pushstring(L, e.what());
    failed = true;
  } catch (const std::exception& e) {
    // the exit code follows the kind: 130 stopped by a signal, 3 unstable, else 1
    if (dynamic_cast<const InterruptedError*>(&e)) context(L)->interrupted = true;
    if (dynamic_cast<const InstabilityError*>(&e)) context(L)->instability = true;
    luaL_where(L, 1);
    lua_pushstring(L, e.what());
    lua_concat(L, 2);
    failed = true;
  }
  if (failed) return lua_error(L);
  return 0;
}

#define SLENDER_METHOD(name, fn) \
  { name, guarded<fn> }

const luaL_Reg kSimMethods[] = {SLENDER_METHOD("wire", l_wire),
                                SLENDER_METHOD("group", l_group),
                                SLENDER_METHOD("region", l_region),
                                SLENDER_METHOD("bond", l_bond),
                                SLENDER_METHOD("pair", l_pair),
                                SLENDER_METHOD("fix", l_fix),
                                SLENDER_METHOD("mesh", l_mesh),
                                SLENDER_METHOD("shell", l_shell),
                                SLENDER_METHOD("growth", l_growth),
                                SLENDER_METHOD("unfix", l_unfix),
                                SLENDER_METHOD("compute", l_compute),
                                SLENDER_METHOD("dump", l_dump),
                                SLENDER_METHOD("integrator", l_integrator),
                                SLENDER_METHOD("modify", l_modify),
                                SLENDER_METHOD("thermo", l_thermo),
                                SLENDER_METHOD("guard", l_guard),
                                SLENDER_METHOD("run", l_run),
                                SLENDER_METHOD("minimize", l_minimize),
                                SLENDER_METHOD("continuation", l_continuation),
                                SLENDER_METHOD("lowest_stiffness", l_lowest_stiffness),
                                SLENDER_METHOD("value", l_value),
                                SLENDER_METHOD("write_dump", l_write_dump),
                                SLENDER_METHOD("position", l_position),
                                SLENDER_METHOD("velocity", l_velocity),
                                SLENDER_METHOD("force", l_force),
                                SLENDER_METHOD("set_position", l_set_position),
                                SLENDER_METHOD("frame", l_frame),
                                SLENDER_METHOD("set_frame", l_set_frame),
                                SLENDER_METHOD("chain_node", l_chain_node),
                                SLENDER_METHOD("nnodes", l_nnodes),
                                SLENDER_METHOD("step", l_step),
                                SLENDER_METHOD("time", l_time),
                                SLENDER_METHOD("dt", l_dt),
                                SLENDER_METHOD("suggest_dt", l_suggest_dt),
                                SLENDER_METHOD("properties", l_properties),
                                SLENDER_METHOD("write_checkpoint", l_write_checkpoint),
                                SLENDER_METHOD("read_checkpoint", l_read_checkpoint),
                                {nullptr, nullptr}};

// slender.plugin(path): loads a style plugin; returns how many styles it registered.
int l_plugin(lua_State* L) {
  lua_pushinteger(L, load_plugin(luaL_checkstring(L, 1)));
  return 1;
}

const luaL_Reg kModule[] = {SLENDER_METHOD("plugin", l_plugin),
                            SLENDER_METHOD("simulation", l_simulation),
                            SLENDER_METHOD("var", l_var),
                            SLENDER_METHOD("clock", l_clock),
                            SLENDER_METHOD("interrupted", l_interrupted),
                            SLENDER_METHOD("result", l_result),
                            SLENDER_METHOD("styles", l_styles),
                            {nullptr, nullptr}};

int open_module(lua_State* L) {
  luaL_newlib(L, kModule);
  lua_pushstring(L, SLENDER_VERSION_STRING);
  lua_setfield(L, -2, "version");
  return 1;
}

int traceback_free_handler(lua_State* L) {
  // keep the message as is: it already names the deck file and line
  if (!lua_isstring(L, 1)) lua_pushstring(L, "(error object is not a string)");
  return 1;
}

}  // namespace

void open_slender(lua_State* L, const DeckOptions& opt) {
  auto* ctx = new DeckContext{opt, {}};
  context(L) = ctx;
  if (luaL_newmetatable(L, kSimMeta)) {
    lua_newtable(L);
    luaL_setfuncs(L, kSimMethods, 0);
    lua_setfield(L, -2, "__index");
    lua_pushcfunction(L, l_gc);
    lua_setfield(L, -2, "__gc");
    lua_pushcfunction(L, l_gc);
    lua_setfield(L, -2, "__close");
  }
  lua_pop(L, 1);
  luaL_requiref(L, "slender", open_module, 1);
  lua_pop(L, 1);
}

void close_slender(lua_State* L) {
  DeckContext* ctx = context(L);
  lua_close(L);  // collects simulations: outputs are flushed and closed
  delete ctx;
}

std::vector<std::string> deck_calls() {
  std::vector<std::string> out;
  for (const luaL_Reg* r = kModule; r->name; ++r) out.push_back(std::string("slender.") + r->name);
  for (const luaL_Reg* r = kSimMethods; r->name; ++r) out.push_back(std::string("sim:") + r->name);
  return out;
}

int run_deck(const DeckOptions& opt) {
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  open_slender(L, opt);
  // decks can require modules that sit next to them
  std::string dir = ".";
  auto slash = opt.path.find_last_of('/');
  if (slash != std::string::npos) dir = opt.path.substr(0, slash);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  std::string path = dir + "/?.lua;" + dir + "/?/init.lua;" + lua_tostring(L, -1);
  lua_pop(L, 1);
  lua_pushstring(L, path.c_str());
  lua_setfield(L, -2, "path");
  lua_pop(L, 1);

  int code = 0;
  // SIGINT / SIGTERM: finish the step, write a last frame and checkpoint, exit 130
  using Handler = void (*)(int);
  Handler old_int = SIG_DFL, old_term = SIG_DFL;
  if (opt.catch_signals) {
    g_stop_signal = 0;
    old_int = std::signal(SIGINT, on_stop_signal);
    old_term = std::signal(SIGTERM, on_stop_signal);
  }
  lua_pushcfunction(L, traceback_free_handler);
  if (luaL_loadfile(L, opt.path.c_str()) != LUA_OK) {
    std::fprintf(stderr, "slender: error: %s\n", lua_tostring(L, -1));
    code = 1;
  } else if (lua_pcall(L, 0, 0, -2) != LUA_OK) {
    const bool stopped = context(L)->interrupted;
    std::fprintf(stderr, "slender: %s: %s\n", stopped ? "stopped" : "error", lua_tostring(L, -1));
    code = stopped ? 130 : context(L)->instability ? 3 : 1;
  }
  std::fflush(stdout);
  DeckContext* ctx = context(L);
  // a -v the deck never read is most likely a typo (-v f=50 for a deck that reads "F"): the
  // run did not use it, and nothing else would say so
  if (code == 0)
    for (const auto& [name, value] : ctx->opt.vars)
      if (!ctx->vars_read.count(name))
        std::fprintf(stderr,
                     "slender: warning: -v %s=%s was never read by the deck (slender.var(\"%s\")); "
                     "the run did not use it\n",
                     name.c_str(), value.c_str(), name.c_str());
  close_slender(L);
  if (opt.catch_signals) {
    std::signal(SIGINT, old_int);
    std::signal(SIGTERM, old_term);
  }
  return code;
}

}  // namespace slender
