// Elastic 2D bending spring at every interior node (docs/models.md §2.1): signed turning
// angle zeta = atan2(e_{i-1} x e_i, e_{i-1}.e_i), moment m = k2 zeta, E = 1/2 k2 zeta^2,
// and the exact nodal forces F_j = -m dzeta/dx_j.
#include <cmath>

#include "chain_select.hpp"
#include "hinge2d.hpp"
#include "registry.hpp"

namespace slender {

class Bend2dBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "elastic 2D bending spring on the signed turning angle of each interior node");
    s.real("k", "bending spring k2 = YI/l0 (moment per radian)").required().positive();
    s.real("damping",
           "bending dashpot gamma_r: the moment gains gamma_r dzeta/dt (docs/models.md §2.1)")
        .def(0.0)
        .nonnegative();
    declare_node_fields(s);
    declare_chains(s);
    return s;
  }
  Bend2dBond(Context& sim, const ParamValues& p)
      : ChainBondStyle(sim, p), k_(p.real("k")), gamma_(p.real("damping")) {
    if (sim.dimension() != 2)
      throw InputError("bond style 'bend2d' needs a 2D simulation (dimension = 2)");
    fields_.bind(sim, p);
  }
  void setup(Context& sim) override {
    ChainBondStyle::setup(sim);
    fields_.rebind(sim);
  }
  const char* energy_category() const override { return "bend"; }

  double compute(Context& sim) override {
    const auto& x = sim.nodes().x;
    const auto& v = sim.nodes().v;
    double energy = 0.0;
    fields_.clear();
    for (auto* c : chains(sim)) {
      // hinge h touches three consecutive chain positions from hinge_first_position(h)
      energy += sim.parallel_chain_forces(
          static_cast<std::size_t>(c->n_hinges()), c->closed, c->n_nodes(), c->closed ? -1 : 0,
          c->closed ? 1 : 2, [&](int, std::size_t begin, std::size_t end, ChainForces& f) {
            double e_part = 0.0;
            for (std::size_t h = begin; h < end; ++h) {
              int a, m, b;
              c->hinge(static_cast<int>(h), a, m, b);
              const Hinge2d g(x[a], x[m], x[b]);
              const double zeta = g.zeta;
              double moment = k_ * zeta;
              // dashpot on the turning rate (docs/models.md §2.1)
              if (gamma_ > 0) moment += gamma_ * g.rate(v, a, m, b);
              g.apply(f, c->hinge_first_position(static_cast<int>(h)), a, m, b, moment);
              e_part += 0.5 * k_ * zeta * zeta;
              if (fields_.on())
                fields_.set(m, zeta / hinge_rest_length(*c, static_cast<int>(h)),
                            0.5 * k_ * zeta * zeta);
            }
            return e_part;
          });
    }
    return energy;
  }
  // E = 1/2 k zeta^2 (the dashpot adds nothing at rest): Hinge2d::add_hessian
  bool add_hessian(Context& sim, Hessian& H) const override {
    const auto& x = sim.nodes().x;
    for (auto* c : chains_now(sim))
      for (int h = 0; h < c->n_hinges(); ++h) {
        int a, m, b;
        c->hinge(h, a, m, b);
        const Hinge2d g(x[a], x[m], x[b]);
        g.add_hessian(H, x[a], x[m], x[b], a, m, b, k_, k_ * g.zeta);
      }
    return true;
  }
  double max_frequency(const Context& sim) const override { return bend_frequency(sim, k_); }

 private:
  double k_, gamma_;
  HingeNodeFields fields_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "bend2d", slender::Bend2dBond)
