// Helpers shared by chain-based styles: which chains a style acts on, and the
// smallest node mass among them (for stable time-step estimates).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "context.hpp"

namespace slender {

// The chains named in `names`, or every chain of the scene when `names` is empty.
template <class Host>  // a Context or a Simulation
std::vector<const Chain*> select_chains(const Host& sim, const std::vector<std::string>& names) {
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

template <class Host>
double min_mass(const Host& sim, const std::vector<const Chain*>& chains) {
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

// A bond style that acts on the chains named in its "chains" parameter (all by
// default): the names are checked at the deck line, bound at every run.
class ChainBondStyle : public BondStyle {
 public:
  static void declare_chains(ParamSpec& s) {
    s.add("chains", ParamType::StringList, "chains it acts on (default: all)")
        .def(std::vector<std::string>{});
  }
  ChainBondStyle(Context& sim, const ParamValues& p) : names_(p.strings("chains")) {
    select_chains(sim, names_);
  }
  void setup(Context& sim) override { chains_ = select_chains(sim, names_); }

 protected:
  // The bound chains; binds on first use outside a run (a direct compute_forces).
  const std::vector<const Chain*>& chains(Context& sim) {
    if (chains_.empty()) setup(sim);
    return chains_;
  }
  // The chains for a const call (add_hessian): the bound ones, else selected now.
  std::vector<const Chain*> chains_now(const Context& sim) const {
    return chains_.empty() ? select_chains(sim, names_) : chains_;
  }
  // Highest mode of a uniform chain of springs k: omega^2 = 4k / m.
  double stretch_frequency(const Context& sim, double k) const {
    auto ch = select_chains(sim, names_);
    return ch.empty() ? 0.0 : 2.0 * std::sqrt(k / min_mass(sim, ch));
  }
  // Zig-zag mode of bending springs k2: zeta = 4u/l, omega^2 = 16 k2 / (m l^2).
  double bend_frequency(const Context& sim, double k) const {
    auto ch = select_chains(sim, names_);
    return ch.empty() ? 0.0 : 4.0 * std::sqrt(k / min_mass(sim, ch)) / min_rest(ch);
  }

  std::vector<std::string> names_;
  std::vector<const Chain*> chains_;
};

}  // namespace slender
