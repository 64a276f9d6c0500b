// Hookean stretching spring on every edge of the selected chains (docs/models.md §2.1, (3.1)):
// E = 1/2 k (|e| - l0)^2; force on the tail node +k(|e|-l0) t, on the head the opposite.
#include <cmath>

#include "chain_select.hpp"
#include "hessian.hpp"
#include "registry.hpp"

namespace slender {

class SpringBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name, "Hookean stretching spring along every edge of a chain");
    s.real("k", "spring stiffness k1 = YA/l0 (force per length)").required().positive();
    declare_chains(s);
    s.output("k", "spring stiffness k (force per length)");
    return s;
  }
  SpringBond(Context& sim, const ParamValues& p) : ChainBondStyle(sim, p), k_(p.real("k")) {}
  const char* energy_category() const override { return "stretch"; }
  double compute(Context& sim) override {
    const auto& x = sim.nodes().x;
    double energy = 0.0;
    for (auto* c : chains(sim)) {
      // edge k touches chain positions k and k + 1
      energy += sim.parallel_chain_forces(
          static_cast<std::size_t>(c->n_edges()), c->closed, c->n_nodes(), 0, 1,
          [&](int, std::size_t begin, std::size_t end, ChainForces& f) {
            double e_part = 0.0;
            for (std::size_t k = begin; k < end; ++k) {
              const int e = static_cast<int>(k);
              const int a = c->edge_tail(e), b = c->edge_head(e);
              const Vec3 d = x[b] - x[a];
              const double len = d.norm();
              const double stretch = len - c->rest_length[k];
              const Vec3 fa = (k_ * stretch / len) * d;
              f.at(static_cast<long>(k), a) += fa;
              f.at(static_cast<long>(k) + 1, b) -= fa;
              e_part += 0.5 * k_ * stretch * stretch;
            }
            return e_part;
          });
    }
    return energy;
  }
  // d^2E/dd^2 = k [n n^T + (1 - l0/|d|)(I - n n^T)] with d = x_b - x_a, n = d/|d|
  // (docs/models.md §9.1); the blocks aa = bb = H, ab = ba = -H.
  bool add_hessian(Context& sim, Hessian& H) const override {
    const auto& x = sim.nodes().x;
    for (auto* c : chains_now(sim))
      for (int e = 0; e < c->n_edges(); ++e) {
        const int a = c->edge_tail(e), b = c->edge_head(e);
        const Vec3 d = x[b] - x[a];
        const double len = d.norm();
        const Vec3 n = d / len;
        const Eigen::Matrix3d nn = n * n.transpose();
        const Eigen::Matrix3d h =
            k_ * (nn + (1.0 - c->rest_length[static_cast<std::size_t>(e)] / len) *
                           (Eigen::Matrix3d::Identity() - nn));
        H.add(a, a, h);
        H.add(b, b, h);
        H.add_pair(a, b, Eigen::Matrix3d(-h));
      }
    return true;
  }
  double max_frequency(const Context& sim) const override { return stretch_frequency(sim, k_); }
  double value(const std::string& key) const override {
    if (key == "k") return k_;
    return BondStyle::value(key);
  }

 private:
  double k_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "spring", slender::SpringBond)
