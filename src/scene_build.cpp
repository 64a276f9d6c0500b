#include "scene_build.hpp"

#ifdef SLENDER_HAVE_SHELL
#include "shell/surface.hpp"
#include "shell/trimesh.hpp"
#endif

#include <cmath>
#include <random>

#include <unistd.h>

namespace slender {

ParamSpec wire_spec() {
  ParamSpec s("command", "wire",
              "sim:wire{...}: a chain of nodes (straight, circular or from points)");
  s.string("name", "chain name (also a node group)").required();
  s.integer("nodes", "number of nodes (not with points)").min(2);
  s.real("spacing", "rest length of each edge").def(1.0).positive();
  s.vector("start", "first node (or circle centre)").def(std::vector<double>{0, 0, 0}).length(2, 3);
  s.vector("direction", "direction of a straight wire")
      .def(std::vector<double>{1, 0, 0})
      .length(2, 3);
  s.real("radius",
         "place the nodes on a closed circle of this radius in the xy plane (closed by itself)")
      .positive();
  s.boolean("closed", "connect the last node to the first").def(false);
  s.real("mass", "mass of each node").def(1.0).positive();
  s.real("perturb", "random displacement amplitude normal to the wire (seeded)")
      .def(0.0)
      .nonnegative();
  s.vector("points", "explicit node positions {{x,y[,z]}, ...} (instead of nodes/spacing)");
  return s;
}

Chain& add_wire(Simulation& sim, const RawParams& raw, std::vector<Vec3> pts) {
  auto p = wire_spec().validate(raw);
  bool closed = p.boolean("closed");
  const bool from_points = !pts.empty();
  if (from_points) {
    // a generated wire's keys would be ignored: say so instead
    for (const char* key : {"nodes", "radius", "spacing", "start", "direction"})
      if (raw.count(key))
        throw InputError(std::string("wire: '") + key +
                         "' describes a generated wire; with points = {...} the points alone "
                         "place the nodes (leave out '" +
                         key + "')");
  } else {
    if (!p.has("nodes")) throw InputError("wire: give either nodes = N or points = {...}");
    const long n = p.integer("nodes");
    // a size that cannot fit is refused with the estimate, not left to std::bad_alloc:
    // position, velocity, force (3 x 24 bytes) and mass per node at the least
    const double need = 80.0 * static_cast<double>(n);
    const double have =
        static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
    if (have > 0 && need > have)
      throw InputError("wire: nodes = " + std::to_string(n) + " needs at least " +
                       std::to_string(need / (1 << 30)) + " GiB, more than this machine's " +
                       std::to_string(have / (1 << 30)) + " GiB of memory");
    const double h = p.real("spacing");
    const Vec3 start = p.vec3("start");
    if (p.has("radius")) {
      if (raw.count("closed") && !closed)
        throw InputError(
            "wire: a wire with a radius is a closed circle; closed = false contradicts it (leave "
            "out closed, or give direction and spacing for a straight wire)");
      const double R = p.real("radius");
      for (long i = 0; i < n; ++i) {
        double a = 2 * M_PI * i / n;
        pts.push_back(start + R * Vec3(std::cos(a), std::sin(a), 0));
      }
      closed = true;
    } else {
      Vec3 dir = p.vec3("direction");
      if (dir.norm() == 0) throw InputError("wire: direction must be non-zero");
      dir.normalize();
      for (long i = 0; i < n; ++i) pts.push_back(start + (h * i) * dir);
    }
  }
  // a 2D scene moves in the xy plane: a z that would be dropped without a word (a tilted
  // direction shortens the wire, points out of the plane fold onto it) is refused instead
  if (sim.dimension() == 2) {
    auto off_plane = [](const Vec3& v) { return v.z() != 0.0; };
    if (!from_points && off_plane(p.vec3("start")))
      throw InputError(
          "wire: start has a z component in a 2D scene (dimension = 2), whose "
          "nodes lie in the xy plane: give {x, y}");
    if (!from_points && !p.has("radius") && off_plane(p.vec3("direction")))
      throw InputError(
          "wire: direction has a z component in a 2D scene (dimension = 2), whose "
          "nodes lie in the xy plane: give {dx, dy}");
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (off_plane(pts[i]))
        throw InputError("wire: point " + std::to_string(i + 1) +
                         " has z = " + std::to_string(pts[i].z()) +
                         " in a 2D scene (dimension = 2), whose nodes lie in the xy plane: give "
                         "{x, y}");
  }
  const double amp = p.real("perturb");
  if (amp > 0) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (size_t i = 1; i + 1 < pts.size(); ++i) {
      Vec3 t = (pts[i + 1] - pts[i - 1]).normalized();
      Vec3 d(u(sim.rng()), u(sim.rng()), sim.dimension() == 3 ? u(sim.rng()) : 0.0);
      d -= d.dot(t) * t;
      pts[i] += amp * d;
    }
  }
  return sim.add_chain(p.str("name"), pts, p.real("mass"), closed);
}

ParamSpec group_spec() {
  ParamSpec s("command", "group", "sim:group(name, {...}): a named set of nodes");
  s.string("chain", "take nodes of this chain (indices below count along it)");
  s.add("nodes", ParamType::IntList, "1-based indices; negative counts from the end");
  s.string("region", "nodes inside this region (intersected with the above)");
  return s;
}

std::size_t add_group(Simulation& sim, const std::string& name, const RawParams& raw) {
  auto p = group_spec().validate(raw);
  // styles take their node lists when they are set up: redefining a group later would leave
  // them on the old nodes without a word, and a chain's or surface's group is its identity
  if (sim.has_group(name)) {
    const bool is_chain = sim.topology().find(name) != nullptr;
    const std::size_t held = sim.group(name).size();
    throw InputError("group '" + name + "' is already defined (" + std::to_string(held) +
                     (held == 1 ? " node, " : " nodes, ") +
                     (name == "all" ? std::string("every node")
                      : is_chain    ? "the nodes of chain '" + name + "'"
                                    : std::string("by an earlier command")) +
                     "): choose another name");
  }
  std::vector<int> sel;
  if (p.has("chain")) {
    Chain* c = sim.topology().find(p.str("chain"));
    if (!c) throw InputError("group '" + name + "': unknown chain '" + p.str("chain") + "'");
    if (p.has("nodes"))
      for (long i : p.integers("nodes"))
        sel.push_back(
            c->nodes[static_cast<std::size_t>(node_index(i, c->nodes.size(), "group " + name))]);
    else
      sel = c->nodes;
  } else if (p.has("nodes")) {
    for (long i : p.integers("nodes"))
      sel.push_back(node_index(i, sim.nodes().size(), "group " + name));
  } else {
    sel = sim.group("all");
  }
  if (p.has("region")) {
    RegionStyle& r = sim.region(p.str("region"));
    std::vector<int> in;
    for (int i : sel)
      if (r.contains(sim.nodes().x[static_cast<std::size_t>(i)])) in.push_back(i);
    sel = in;
  }
  if (sel.empty()) throw InputError("group '" + name + "' would be empty");
  const std::size_t count = sel.size();
  sim.set_group(name, std::move(sel));
  return count;
}

ParamSpec mesh_spec() {
  ParamSpec s("command", "mesh",
              "sim:mesh{...}: a triangle mesh for shells, generated or read from OBJ/OFF, with "
              "its ghost layer (groups <name>, <name>.boundary, <name>.ghost, <name>.row1)");
  s.string("name", "surface name (also the node group of its real nodes)").required();
  s.string("shape", "generated mesh").choices({"disc", "ring", "rectangle", "sphere"});
  s.string("file", "read an OBJ or OFF file instead of generating a shape");
  s.real("radius", "disc or sphere radius; outer radius of a ring").def(1.0).positive();
  s.real("inner_radius", "inner radius of a ring").positive();
  s.vector("size", "rectangle sides {lx, ly}").length(2, 2);
  s.real("edge", "target edge length (disc default: 5 refinements of a hexagon)").positive();
  s.real("refine_center",
         "disc: radius of a core refined refine_levels more times (red-green, level k within "
         "refine_center / 2^(k-1)), to resolve an e-cone's apex (docs/models.md §6.12)")
      .def(0.0)
      .nonnegative();
  s.integer("refine_levels", "disc: extra refinement levels of the core (edge / 2^levels there)")
      .def(0.0)
      .min(0)
      .max(6);
  s.integer("refine", "extra global refinements at edge midpoints (spheres re-projected)")
      .def(0.0)
      .min(0)
      .max(6);
  s.vector("center", "translation applied to the mesh")
      .def(std::vector<double>{0, 0, 0})
      .length(3, 3);
  s.real("noise", "seeded uniform displacement amplitude along the normal (docs/models.md §6.12)")
      .def(0.0)
      .nonnegative();
  s.string("write", "write the control mesh (without ghosts) to this OBJ/OFF file");
  return s;
}

std::pair<int, int> add_mesh(Simulation& sim, const RawParams& raw) {
#ifdef SLENDER_HAVE_SHELL
  auto p = mesh_spec().validate(raw);
  shell::TriMesh m;
  const double R = p.real("radius");
  auto levels = [](double size, double edge) {
    return std::max(0, static_cast<int>(std::ceil(std::log2(size / edge) - 1e-9)));
  };
  if (p.has("file") == p.has("shape")) throw InputError("mesh: give exactly one of shape or file");
  // a target edge the generators cannot reach is refused in the deck's words (it was
  // reported as "refinements must be in [0, 9]", without naming edge)
  auto check_levels = [&](int need, int most, double size, const char* what) {
    if (need > most)
      throw InputError("mesh: edge = " + std::to_string(p.real("edge")) + " on a " + what +
                       " of radius " + std::to_string(R) + " needs " + std::to_string(need) +
                       " refinements, at most " + std::to_string(most) +
                       " are made (edge >= " + std::to_string(size / std::pow(2.0, most)) + ")");
  };
  // Triangles after the extra refinements: each global one makes four of a triangle, and a
  // disc's core refinement adds about four times the core's share per level (each level
  // refines half the radius of the one before). A count past 2e7 is refused before any
  // memory is taken, naming the keys that lead to it.
  const double grow = std::pow(4.0, static_cast<double>(p.integer("refine"))) *
                      (p.has("shape") && p.str("shape") == "disc" && p.real("refine_center") > 0
                           ? 1.0 + 4.0 * static_cast<double>(p.integer("refine_levels")) *
                                       std::min(1.0, std::pow(p.real("refine_center") / R, 2))
                           : 1.0);
  auto check_cells = [&](double base, const char* what) {
    const double cells = base * grow;
    if (cells > 2e7) {
      std::string keys = p.has("edge") ? "edge = " + std::to_string(p.real("edge")) : "";
      auto add = [&](const std::string& k) { keys += (keys.empty() ? "" : ", ") + k; };
      if (p.integer("refine") > 0) add("refine = " + std::to_string(p.integer("refine")));
      if (grow > std::pow(4.0, static_cast<double>(p.integer("refine"))))
        add("refine_levels = " + std::to_string(p.integer("refine_levels")) +
            " within refine_center = " + std::to_string(p.real("refine_center")));
      throw InputError("mesh: " + (keys.empty() ? std::string("the defaults") : keys) + " give a " +
                       what + " of about " + std::to_string(cells) +
                       " triangles (at most 2e7): choose a larger edge or fewer refinements");
    }
  };
  if (p.has("file")) {
    m = shell::read_mesh(p.str("file"));
    check_cells(static_cast<double>(m.tri.size()), "mesh");
  } else if (p.str("shape") == "disc") {
    if (p.has("edge")) check_levels(levels(R, p.real("edge")), 9, R, "disc");
    const int L = p.has("edge") ? levels(R, p.real("edge")) : 5;
    check_cells(6.0 * std::pow(4.0, L), "disc");
    m = shell::make_disc(R, L, p.real("refine_center"),
                         static_cast<int>(p.integer("refine_levels")));
  } else if (p.str("shape") == "ring") {
    if (!p.has("inner_radius")) throw InputError("mesh: a ring needs inner_radius");
    const double ri = p.real("inner_radius");
    const double e = p.has("edge") ? p.real("edge") : R / 16;
    check_cells(2.0 * std::ceil((R - ri) / e) * std::ceil(2 * M_PI * R / e), "ring");
    m = shell::make_ring(ri, R, std::max(1, static_cast<int>(std::ceil((R - ri) / e))),
                         std::max(6, static_cast<int>(std::ceil(2 * M_PI * R / e))));
  } else if (p.str("shape") == "rectangle") {
    if (!p.has("size")) throw InputError("mesh: a rectangle needs size = {lx, ly}");
    auto sz = p.vec("size");
    const double e = p.has("edge") ? p.real("edge") : std::min(sz[0], sz[1]) / 8;
    check_cells(2.0 * std::ceil(sz[0] / e) * std::ceil(sz[1] / e), "rectangle");
    m = shell::make_rectangle(sz[0], sz[1], std::max(2, static_cast<int>(std::ceil(sz[0] / e))),
                              std::max(2, static_cast<int>(std::ceil(sz[1] / e))));
  } else {
    if (p.has("edge"))
      check_levels(std::max(1, levels(1.05 * R, p.real("edge"))), 8, 1.05 * R, "sphere");
    const int L = p.has("edge") ? std::max(1, levels(1.05 * R, p.real("edge"))) : 3;
    check_cells(20.0 * std::pow(4.0, L), "sphere");
    m = shell::make_sphere(R, L);
  }
  for (long r = 0; r < p.integer("refine"); ++r) {
    shell::refine(m);
    if (p.has("shape") && p.str("shape") == "sphere")
      for (Vec3& x : m.x) x *= R / x.norm();
  }
  const Vec3 c = p.vec3("center");
  for (Vec3& x : m.x) x += c;
  if (p.has("write")) shell::write_mesh(p.str("write"), m);
  auto& s = shell::add_surface(sim, p.str("name"), m, p.real("noise"));
  return {s.mesh->n_real_nodes, s.mesh->n_real_tris};
#else
  (void)sim;
  (void)raw;
  throw InputError(
      "mesh: this slender was built without the shell family (-DSLENDER_WITH_SHELL=ON)");
#endif
}

int node_index(long i, std::size_t n, const std::string& what) {
  long k = i > 0 ? i - 1 : static_cast<long>(n) + i;
  if (i == 0 || k < 0 || k >= static_cast<long>(n))
    throw InputError(what + ": node index " + std::to_string(i) + " out of range 1.." +
                     std::to_string(n) + " (or -1..-" + std::to_string(n) + ")");
  return static_cast<int>(k);
}

}  // namespace slender
