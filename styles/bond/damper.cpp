// Internal (Kelvin-Voigt) damping along the chain: on every edge, -gamma (v_tail - v_head)
// on the tail and the opposite on the head. It damps the relative motion of neighbours
// (stretching and bending vibrations) and leaves a rod that slides along its own length
// free, where a drag on absolute velocities (fix damping/viscous) resists the sliding
// with gamma v per moving node. Dissipative: no energy.
#include "chain_select.hpp"
#include "registry.hpp"

namespace slender {

class DamperBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "internal damping: -gamma (v_i - v_j) between the two nodes of every edge "
                "(damps vibrations, not rigid sliding along the chain)");
    s.real("gamma", "damping coefficient (force per relative velocity)").required().nonnegative();
    declare_chains(s);
    s.output("gamma", "damping coefficient gamma (force per relative velocity)");
    return s;
  }
  DamperBond(Context& sim, const ParamValues& p)
      : ChainBondStyle(sim, p), gamma_(p.real("gamma")) {}
  const char* energy_category() const override { return "damping"; }
  double compute(Context& sim) override {
    auto& v = sim.nodes().v;
    auto& f = sim.nodes().f;
    for (auto* c : chains(sim)) {
      const int ne = c->n_edges();
      for (int e = 0; e < ne; ++e) {
        const int a = c->edge_tail(e), b = c->edge_head(e);
        const Vec3 fa = -gamma_ * (v[a] - v[b]);
        f[a] += fa;
        f[b] -= fa;
      }
    }
    return 0.0;
  }
  // explicit schemes need 4 gamma dt / m below ~1 (a node between two dampers, zig-zag)
  double max_frequency(const Context& sim) const override {
    auto ch = select_chains(sim, names_);
    return ch.empty() ? 0.0 : 4.0 * gamma_ / min_mass(sim, ch);
  }
  double value(const std::string& key) const override {
    if (key == "gamma") return gamma_;
    return BondStyle::value(key);
  }

 private:
  double gamma_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "damper", slender::DamperBond)
