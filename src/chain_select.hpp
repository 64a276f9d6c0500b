// Helpers shared by chain-based styles: which chains a style acts on, and the
// smallest node mass among them (for stable time-step estimates).
#pragma once

#include <string>
#include <vector>

#include "simulation.hpp"

namespace slender {

// The chains named in `names`, or every chain of the scene when `names` is empty.
inline std::vector<const Chain*> select_chains(const Simulation& sim,
                                               const std::vector<std::string>& names) {
  std::vector<const Chain*> out;
  auto& topo = sim.topology();
  for (auto& c : topo.chains) {
    bool take = names.empty();
    for (auto& n : names) take = take || n == c.name;
    if (take) out.push_back(&c);
  }
  for (auto& n : names) {
    bool found = false;
    for (auto& c : topo.chains) found = found || c.name == n;
    if (!found) throw InputError("unknown chain '" + n + "'");
  }
  return out;
}

inline double min_mass(const Simulation& sim, const std::vector<const Chain*>& chains) {
  double m = 1e300;
  for (auto* c : chains)
    for (int i : c->nodes) m = std::min(m, sim.nodes().mass[i]);
  return m;
}

inline double min_rest(const std::vector<const Chain*>& chains) {
  double l = 1e300;
  for (auto* c : chains)
    for (double r : c->rest_length) l = std::min(l, r);
  return l;
}

}  // namespace slender
