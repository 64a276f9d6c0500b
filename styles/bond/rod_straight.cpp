// Bending of a naturally straight, isotropic 3D rod without directors (a discrete
// elastic rod after Bergou et al., extensible; docs/models.md §3): at each interior node
// the curvature binormal kb = 2 e0 x e1 / (|e0||e1| + e0.e1) (§3.1), bending energy
// E = YI |kb|^2 / l over the rest vertex length l = |e0_rest| + |e1_rest| (§3.2), and
// forces from the exact gradients of kb (§3.3). Positions only: twist is taken as
// relaxed, so a scene with this style allocates no orientation data. Stretching
// is the `spring` style (k = YA / l0, docs/models.md §3.3 (4.7)).
#include <Eigen/Geometry>
#include <cmath>
#include <unsupported/Eigen/AutoDiff>

#include "chain_select.hpp"
#include "hessian.hpp"
#include "registry.hpp"

namespace slender {

class StraightRodBond : public ChainBondStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("bond", name,
                "bending of a straight isotropic rod without directors: discrete elastic rod "
                "curvature binormal, E = YI |kb|^2 / l (docs/models.md §3)");
    s.real("YI", "bending stiffness Y I (moment times length)").required().positive();
    s.boolean("node_energy",
              "keep each node's bending energy in the node property bend.energy (for dumps "
              "and energy distributions; off: nothing allocated)")
        .def(false);
    declare_chains(s);
    return s;
  }
  StraightRodBond(Context& sim, const ParamValues& p) : ChainBondStyle(sim, p), yi_(p.real("YI")) {
    if (p.boolean("node_energy")) node_energy_ = &sim.nodes().require<double>("bend.energy", 0.0);
  }
  const char* energy_category() const override { return "bend"; }

  double compute(Context& sim) override {
    const auto& x = sim.nodes().x;
    double energy = 0.0;
    if (node_energy_)
      for (auto& e : node_energy_->values()) e = 0.0;
    for (auto* c : chains(sim)) {
      const int ne = c->n_edges();
      // hinge h touches three consecutive chain positions from hinge_first_position(h)
      energy += sim.parallel_chain_forces(
          static_cast<std::size_t>(c->n_hinges()), c->closed, c->n_nodes(), c->closed ? -1 : 0,
          c->closed ? 1 : 2, [&](int, std::size_t begin, std::size_t end, ChainForces& f) {
            double e_part = 0.0;
            for (std::size_t k = begin; k < end; ++k) {
              const int h = static_cast<int>(k);
              int a, m, b;
              c->hinge(h, a, m, b);
              // rest lengths of the two edges at this hinge (§3.1: domain lengths at rest)
              const int e0i = c->closed ? (h - 1 + ne) % ne : h;
              const int e1i = c->closed ? h : h + 1;
              const double l = c->rest_length[e0i] + c->rest_length[e1i];
              const Vec3 e0 = x[m] - x[a], e1 = x[b] - x[m];
              const double n0 = e0.norm(), n1 = e1.norm();
              const double D = n0 * n1 + e0.dot(e1);
              if (!(D > 1e-12 * n0 * n1)) continue;  // a fully folded hinge has no binormal
              const Vec3 kb = 2.0 * e0.cross(e1) / D;
              const double e_hinge = yi_ * kb.squaredNorm() / l;  // (4.4)
              e_part += e_hinge;
              if (node_energy_) (*node_energy_)[m] = e_hinge;
              // exact gradients (§3.3); F_k = -(2 YI / l) (grad_k kb)^T kb. With [e]^T = -[e]:
              // (grad_{i-1} kb)^T kb = (2 kb x e1 + |kb|^2 (e1 + |e1| t0)) / D and
              // (grad_{i+1} kb)^T kb = (2 kb x e0 - |kb|^2 (e0 + |e0| t1)) / D
              const double kb2 = kb.squaredNorm();
              const double s = 2.0 * yi_ / (l * D);
              const Vec3 fa = -s * (2.0 * kb.cross(e1) + kb2 * (e1 + (n1 / n0) * e0));
              const Vec3 fb = -s * (2.0 * kb.cross(e0) - kb2 * (e0 + (n0 / n1) * e1));
              const long p = c->hinge_first_position(h);
              f.at(p, a) += fa;
              f.at(p + 2, b) += fb;
              f.at(p + 1, m) -= fa + fb;
            }
            return e_part;
          });
    }
    return energy;
  }
  // The exact Hessian by forward automatic differentiation of the hinge forces above
  // (Eigen's AutoDiffScalar, nine directions: the three nodes' coordinates), exact to
  // round-off like the forces themselves (docs/models.md §9.6).
  bool add_hessian(Context& sim, Hessian& H) const override {
    using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 9, 1>>;
    using V = Eigen::Matrix<AD, 3, 1>;
    const auto& x = sim.nodes().x;
    for (auto* c : chains_now(sim)) {
      const int ne = c->n_edges();
      for (int h = 0; h < c->n_hinges(); ++h) {
        int a, m, b;
        c->hinge(h, a, m, b);
        const int e0i = c->closed ? (h - 1 + ne) % ne : h;
        const int e1i = c->closed ? h : h + 1;
        const double l = c->rest_length[e0i] + c->rest_length[e1i];
        V xa, xm, xb;
        for (int k = 0; k < 3; ++k) {
          xa[k] = AD(x[a][k], 9, k);
          xm[k] = AD(x[m][k], 9, 3 + k);
          xb[k] = AD(x[b][k], 9, 6 + k);
        }
        const V e0 = xm - xa, e1 = xb - xm;
        const AD n0 = sqrt(e0.squaredNorm()), n1 = sqrt(e1.squaredNorm());
        const AD D = n0 * n1 + e0.dot(e1);
        if (!(D.value() > 1e-12 * n0.value() * n1.value())) continue;
        const V kb = AD(2.0) * e0.cross(e1) / D;
        const AD kb2 = kb.squaredNorm();
        const AD s = AD(2.0 * yi_ / l) / D;
        const V fa = -s * (AD(2.0) * kb.cross(e1) + kb2 * (e1 + (n1 / n0) * e0));
        const V fb = -s * (AD(2.0) * kb.cross(e0) - kb2 * (e0 + (n0 / n1) * e1));
        // rows: -d f / d x for the nodes a, m, b (f_m = -(f_a + f_b))
        const int node[3] = {a, m, b};
        for (int col = 0; col < 3; ++col) {
          Eigen::Matrix3d Ha, Hb;
          for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) {
              Ha(r, k) = -fa[r].derivatives()[3 * col + k];
              Hb(r, k) = -fb[r].derivatives()[3 * col + k];
            }
          H.add(a, node[col], Ha);
          H.add(b, node[col], Hb);
          H.add(m, node[col], Eigen::Matrix3d(-Ha - Hb));
        }
      }
    }
    return true;
  }
  // zig-zag mode: a small turning angle phi stores YI phi^2 / (2 l0), i.e. k2 = YI / l0
  double max_frequency(const Context& sim) const override {
    auto ch = select_chains(sim, names_);
    return ch.empty() ? 0.0 : bend_frequency(sim, yi_ / min_rest(ch));
  }

 private:
  double yi_;
  Property<double>* node_energy_ = nullptr;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::BondStyle, "rod/straight", slender::StraightRodBond)
