// Fuzz target: the parameters a deck gives as a Lua table. The input is a Lua expression
// (after a first byte that chooses the deck command it is given to); it is evaluated in an
// empty environment (no library, no slender module, a bounded number of instructions and
// bytes) and the value is passed to that command of a small scene, which then runs a few
// steps. Every input must either work or be refused with a Lua error (the deck's one-line
// message); a crash or a sanitizer report is a finding.
#include <lua.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "lua_binding.hpp"

namespace {

// The scenes: `T` is the fuzzed value. Each builds a scene around one command's table.
const char* const kTemplates[] = {
    // simulation options
    "local sim = S.simulation(T) sim:wire{name='w', nodes=5, spacing=1}"
    " sim:integrator('verlet', {dt=0.01}) sim:run(2)",
    // a wire from geometry (a valid but long wire, up to the memory check's limit, is cut
    // to 10^4 nodes: 3e6 nodes take 30 s under the sanitizers; 1e9 and more still reach
    // the check)
    "local sim = S.simulation{dimension=2, quiet=true}"
    " if type(T) == 'table' and math.type(T.nodes) and T.nodes > 1e4 and T.nodes < 1e9 then"
    "  T.nodes = 10000 end sim:wire(T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(2)",
    // bonds
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', T) sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:bond('bend2d/hysteresis', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=3, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:bond('rod/cosserat', T)"
    " sim:integrator('verlet', {dt=0.001}) sim:run(3)",
    // contacts and walls
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', radius=3, nodes=40,"
    " closed=true} sim:bond('spring', {k=100}) sim:pair('contact/node-edge', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=3, quiet=true} sim:wire{name='w', nodes=20, spacing=0.3}"
    " sim:bond('spring', {k=100}) sim:pair('contact/segment', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=0.3}"
    " sim:bond('spring', {k=100}) sim:fix('wall', 'wall/circle', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    // fixes
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:fix('c', 'clamp', T) sim:fix('f', 'force/constant',"
    " {group='all', force={0, 1}}) sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:fix('f', 'force/constant', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='wire', nodes=17,"
    " spacing=1, start={-8, 0}} sim:bond('spring', {k=100}) sim:fix('feed', 'inject/wire', T)"
    " sim:integrator('verlet', {dt=0.01}) sim:run(3)",
    // groups, integrators, the run and the guard (at most 3 steps: the harness times inputs)
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:group('g', T) sim:integrator('verlet', {dt=0.01}) sim:run(1)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:integrator('gear', T) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:integrator('verlet', {dt=0.01}) sim:guard(T) sim:run(3)",
    "local sim = S.simulation{dimension=2, quiet=true} sim:wire{name='w', nodes=6, spacing=1}"
    " sim:bond('spring', {k=100}) sim:integrator('verlet', {dt=0.01})"
    " if type(T) == 'table' then T.steps = 3 elseif type(T) == 'number' then T = math.min(T, 3)"
    " end sim:run(T)",
    // shells
    // a valid but large mesh (a deck may ask for up to 2e7 triangles) would spend the
    // harness's time limit in building it: such sizes are made coarse here, while sizes past
    // the limit (and every other key) still reach the checks
    "local sim = S.simulation{dimension=3, quiet=true}"
    " if type(T) == 'table' then"
    "  if math.type(T.refine) and T.refine >= 2 and T.refine <= 6 then T.refine = 1 end"
    "  if math.type(T.refine_levels) and T.refine_levels >= 3 and T.refine_levels <= 6 then"
    "   T.refine_levels = 2 end"
    "  local s = 1"
    "  if math.type(T.radius) and T.radius == T.radius then s = math.max(s, math.abs(T.radius)) end"
    "  if type(T.size) == 'table' then for _, v in ipairs(T.size) do"
    "   if math.type(v) and v == v then s = math.max(s, math.abs(v)) end end end"
    "  local e = T.edge"
    "  if math.type(e) and e > 0 and s / e > 16 and s / e < 1e5 then T.edge = s / 16 end"
    " end sim:mesh(T)",
    "local sim = S.simulation{dimension=3, quiet=true} sim:mesh{name='s', shape='disc',"
    " radius=1, edge=0.5} sim:shell('koiter', T) sim:integrator('newmark', {dt=1e-4})"
    " sim:run(2)",
};
constexpr std::size_t kScenes = sizeof(kTemplates) / sizeof(kTemplates[0]);

// The fuzzed expression may not allocate without bound.
struct Budget {
  std::size_t used = 0;
};
constexpr std::size_t kMaxBytes = 32u << 20;

void* bounded_alloc(void* ud, void* ptr, std::size_t old_size, std::size_t new_size) {
  auto* b = static_cast<Budget*>(ud);
  if (ptr) b->used -= old_size;
  if (new_size == 0) {
    std::free(ptr);
    return nullptr;
  }
  if (b->used + new_size > kMaxBytes) {
    if (ptr) b->used += old_size;
    return nullptr;
  }
  void* p = std::realloc(ptr, new_size);
  b->used += p ? new_size : (ptr ? old_size : 0);
  return p;
}

void stop_runaway(lua_State* L, lua_Debug*) {
  luaL_error(L, "instruction budget exceeded");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2 || size > 4096) return 0;
  const char* scene = kTemplates[data[0] % kScenes];
  const std::string expr(reinterpret_cast<const char*>(data) + 1, size - 1);
  Budget budget;
  lua_State* L = lua_newstate(bounded_alloc, &budget);
  if (!L) return 0;
  luaL_requiref(L, LUA_GNAME, luaopen_base, 1);
  luaL_requiref(L, LUA_TABLIBNAME, luaopen_table, 1);
  luaL_requiref(L, LUA_MATHLIBNAME, luaopen_math, 1);
  lua_pop(L, 3);
  slender::DeckOptions opt;
  opt.quiet = true;
  opt.threads = 1;
  opt.catch_signals = false;
  slender::open_slender(L, opt);
  lua_sethook(L, stop_runaway, LUA_MASKCOUNT, 2000000);
  // the value, evaluated in an empty environment
  const std::string chunk = "return " + expr;
  if (luaL_loadbufferx(L, chunk.data(), chunk.size(), "=fuzz", "t") == LUA_OK) {
    lua_newtable(L);  // _ENV of the expression: nothing
    lua_setupvalue(L, -2, 1);
    if (lua_pcall(L, 0, 1, 0) == LUA_OK) {
      lua_setglobal(L, "T");
      // the scene sees the module as S and the value as T, nothing that reaches files or
      // code (no io, os, load, require: none of them is opened or they are removed)
      const std::string prelude =
          "local S, T = slender, T; slender, print, load, dofile, loadfile, require, "
          "collectgarbage = nil; ";
      const std::string code = prelude + scene;
      if (luaL_loadbufferx(L, code.data(), code.size(), "=scene", "t") == LUA_OK)
        lua_pcall(L, 0, 0, 0);
    }
  }
  // SLENDER_FUZZ_VERBOSE=1: what each input gave (to check that the seeds run their scene)
  if (std::getenv("SLENDER_FUZZ_VERBOSE"))
    std::fprintf(stderr, "scene %d: %s\n", data[0] % static_cast<int>(kScenes),
                 lua_gettop(L) > 0 && lua_isstring(L, -1) ? lua_tostring(L, -1) : "ok");
  slender::close_slender(L);
  return 0;
}
