// Elastic 2D bending spring at every interior node (MODELS.md §2.1): signed turning
// angle zeta = atan2(e_{i-1} x e_i, e_{i-1}.e_i), moment m = k2 zeta, E = 1/2 k2 zeta^2,
// and the exact nodal forces F_j = -m dzeta/dx_j.
#include <cmath>

#include "chain_select.hpp"
#include "registry.hpp"

namespace slender {

class Bend2dBond : public BondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "elastic 2D bending spring on the signed turning angle of each interior node");
    s.real("k", "bending spring k2 = YI/l0 (moment per radian)").required().positive();
    s.real("damping", "bending dashpot gamma_r: the moment gains gamma_r dzeta/dt (MODELS.md §2.1)")
        .def(0.0)
        .nonnegative();
    s.add("chains", ParamType::StringList, "chains it acts on (default: all)")
        .def(std::vector<std::string>{});
    return s;
  }
  Bend2dBond(Simulation& sim, const ParamValues& p)
      : k_(p.real("k")), gamma_(p.real("damping")), names_(p.strings("chains")) {
    if (sim.dimension() != 2)
      throw InputError("bond style 'bend2d' needs a 2D simulation (dimension = 2)");
    select_chains(sim, names_);
  }
  void setup(Simulation& sim) override { chains_ = select_chains(sim, names_); }
  const char* energy_category() const override { return "bend"; }

  double compute(Simulation& sim) override {
    if (chains_.empty()) setup(sim);
    auto& x = sim.nodes().x;
    auto& f = sim.nodes().f;
    double energy = 0.0;
    for (auto* c : chains_) {
      const int nh = c->n_hinges();
      for (int h = 0; h < nh; ++h) {
        int a, m, b;
        c->hinge(h, a, m, b);
        const Eigen::Vector2d e0 = (x[m] - x[a]).head<2>();
        const Eigen::Vector2d e1 = (x[b] - x[m]).head<2>();
        const double cross = e0.x() * e1.y() - e0.y() * e1.x();
        const double zeta = std::atan2(cross, e0.dot(e1));
        double moment = k_ * zeta;
        // dzeta/dx_b = z x e1/|e1|^2, dzeta/dx_a = z x e0/|e0|^2, z x v = (-v_y, v_x)
        const Eigen::Vector2d gb = Eigen::Vector2d(-e1.y(), e1.x()) / e1.squaredNorm();
        const Eigen::Vector2d ga = Eigen::Vector2d(-e0.y(), e0.x()) / e0.squaredNorm();
        // dashpot on the turning rate: dzeta/dt = sum_j dzeta/dx_j . v_j
        if (gamma_ > 0) moment += gamma_ * turning_rate(sim, a, m, b, ga, gb);
        f[b].head<2>() -= moment * gb;
        f[a].head<2>() -= moment * ga;
        f[m].head<2>() += moment * (ga + gb);
        energy += 0.5 * k_ * zeta * zeta;
      }
    }
    return energy;
  }
  double max_frequency(const Simulation& sim) const override {
    auto ch = select_chains(sim, names_);
    if (ch.empty()) return 0.0;
    // zig-zag mode: zeta = 4u/l, so omega^2 = 16 k2 / (m l^2)
    return 4.0 * std::sqrt(k_ / min_mass(sim, ch)) / min_rest(ch);
  }

 private:
  static double turning_rate(const Simulation& sim, int a, int m, int b, const Eigen::Vector2d& ga,
                             const Eigen::Vector2d& gb) {
    auto& v = sim.nodes().v;
    return gb.dot(v[b].head<2>()) + ga.dot(v[a].head<2>()) - (ga + gb).dot(v[m].head<2>());
  }

  double k_, gamma_;
  std::vector<std::string> names_;
  std::vector<const Chain*> chains_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "bend2d", slender::Bend2dBond)
