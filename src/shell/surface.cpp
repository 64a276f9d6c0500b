#include "shell/surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <random>

#include "simulation.hpp"

namespace slender::shell {

Surface& add_surface(Simulation& sim, const std::string& name, const TriMesh& mesh, double noise) {
  if (sim.dimension() != 3) throw InputError("mesh: shells need a 3D simulation");
  if (sim.topology().find_surface(name) || sim.has_group(name))
    throw InputError("mesh: the name '" + name + "' is already used");
  // a collapsed triangle has no tangent plane: refuse it here, not as NaN later
  for (int t = 0; t < mesh.n_tris(); ++t) {
    const auto& tr = mesh.tri[t];
    const Vec3 a = mesh.x[tr[1]] - mesh.x[tr[0]], b = mesh.x[tr[2]] - mesh.x[tr[0]];
    const double longest = std::max({a.squaredNorm(), b.squaredNorm(), (a - b).squaredNorm()});
    if (!(a.cross(b).norm() > 1e-10 * longest))
      throw InputError("mesh '" + name + "': triangle " + std::to_string(t + 1) + " (nodes " +
                       std::to_string(tr[0] + 1) + " " + std::to_string(tr[1] + 1) + " " +
                       std::to_string(tr[2] + 1) +
                       ") is degenerate (zero area): merge or move its nodes");
  }
  auto g = std::make_shared<GhostedMesh>(add_ghosts(mesh));
  check_patches(*g);
  Surface s;
  s.name = name;
  s.mesh = g;
  s.first_node = static_cast<int>(sim.nodes().size());
  // area-weighted node normals for the noise direction
  std::vector<Vec3> normal(g->n_real_nodes, Vec3::Zero());
  for (int t = 0; t < g->n_real_tris; ++t) {
    const auto& tr = g->mesh.tri[t];
    const Vec3 n = (g->mesh.x[tr[1]] - g->mesh.x[tr[0]]).cross(g->mesh.x[tr[2]] - g->mesh.x[tr[0]]);
    for (int k : tr) normal[k] += n;
  }
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int i = 0; i < g->mesh.n_nodes(); ++i) {
    Vec3 x = g->mesh.x[i];
    if (i < g->n_real_nodes && noise > 0 && normal[i].norm() > 0)
      x += noise * uni(sim.rng()) * normal[i].normalized();
    sim.nodes().add(x, 1.0);
  }
  // ghosts follow the perturbed real nodes through the mirror rule
  for (auto& gh : g->ghosts)
    sim.nodes().x[s.first_node + gh.node] = sim.nodes().x[s.first_node + gh.b0] +
                                            sim.nodes().x[s.first_node + gh.b2] -
                                            sim.nodes().x[s.first_node + gh.interior];
  auto shift = [&](const std::vector<int>& ids) {
    std::vector<int> out;
    for (int i : ids) out.push_back(s.first_node + i);
    return out;
  };
  std::vector<int> real, ghosts;
  for (int i = 0; i < g->n_real_nodes; ++i) real.push_back(s.first_node + i);
  for (auto& gh : g->ghosts) ghosts.push_back(s.first_node + gh.node);
  sim.set_group(name, real);
  sim.set_group(name + ".boundary", shift(g->boundary));
  sim.set_group(name + ".ghost", ghosts);
  sim.set_group(name + ".row1", shift(g->first_row));
  sim.topology().surfaces.push_back(s);
  return sim.topology().surfaces.back();
}

}  // namespace slender::shell
