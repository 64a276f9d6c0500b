// Morphology observables of a 2D wire in a circular cavity (docs/models.md §2.7):
// A and B, the total squared curvature sum kappa_i^2 l0 of the hinges in the inner
// disc of radius r / sqrt(2) and in the outer ring (equal areas); classic when
// A / B < 0.5 (curvature near the wall). Spiral indicator: the winding |sum zeta_i| /
// 2 pi of each half of the wire inside the cavity (the two arms of a double spiral
// turn in opposite senses along the wire, so the net winding of a double spiral is
// ~0); "winding" is the larger of the two, "net_winding" the whole wire's.
#include <algorithm>
#include <cmath>

#include "chain_select.hpp"
#include "hinge2d.hpp"
#include "registry.hpp"

namespace slender {

class Morphology2dCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "2D crumpling morphology: A/B curvature criterion (classic vs plastic) and net "
                "winding (spiral), docs/models.md §2.7");
    s.real("radius", "cavity radius r").required().positive();
    s.vector("center", "cavity centre").def(std::vector<double>{0, 0}).length(2, 3);
    s.add("chains", ParamType::StringList, "chains to analyse (default: all)")
        .def(std::vector<std::string>{});
    s.output("A", "sum of kappa^2 l0 over the hinges in the inner disc r < R / sqrt(2)");
    s.output("B", "sum of kappa^2 l0 over the hinges in the outer ring of the cavity");
    s.output("ratio", "A / B (1e300 when B = 0 < A)");
    s.output("classic", "1 when A / B < 0.5 (classic morphology), else 0");
    s.output("winding", "largest |winding| of either half of a wire inside the cavity, in turns");
    s.output("net_winding", "|net winding| of the wire inside the cavity, in turns");
    return s;
  }
  Morphology2dCompute(Simulation& sim, const ParamValues& p)
      : r_(p.real("radius")), c_(p.vec3("center")), names_(p.strings("chains")) {
    if (sim.dimension() != 2)
      throw InputError("compute style 'morphology2d' needs a 2D simulation");
    select_chains(sim, names_);
  }
  void evaluate(Simulation& sim) override {
    A_ = B_ = winding_ = net_ = 0.0;
    auto& x = sim.nodes().x;
    const double r_inner2 = 0.5 * r_ * r_;
    double net = 0.0;
    for (auto* c : select_chains(sim, names_)) {
      double half[2] = {0.0, 0.0};
      const int nh = c->n_hinges();
      for (int h = 0; h < nh; ++h) {
        int a, m, b;
        c->hinge(h, a, m, b);
        const double r2 = (x[m] - c_).head<2>().squaredNorm();
        if (r2 >= r_ * r_) continue;  // only the wire inside the cavity
        const double zeta = Hinge2d(x[a], x[m], x[b]).zeta;
        const int ne = c->n_edges();
        const double l0 = c->closed ? 0.5 * (c->rest_length[(h - 1 + ne) % ne] + c->rest_length[h])
                                    : 0.5 * (c->rest_length[h] + c->rest_length[h + 1]);
        const double sq = zeta * zeta / l0;  // kappa^2 l0 with kappa = zeta / l0
        (r2 < r_inner2 ? A_ : B_) += sq;
        half[2 * h < nh ? 0 : 1] += zeta;
      }
      net += half[0] + half[1];
      winding_ =
          std::max({winding_, std::abs(half[0]) / (2 * M_PI), std::abs(half[1]) / (2 * M_PI)});
    }
    net_ = std::abs(net) / (2 * M_PI);
  }
  double value(const std::string& key) const override {
    if (key == "A") return A_;
    if (key == "B") return B_;
    if (key == "ratio") return B_ > 0 ? A_ / B_ : (A_ > 0 ? 1e300 : 0.0);
    if (key == "classic") return (B_ > 0 && A_ / B_ < 0.5) ? 1.0 : 0.0;
    if (key == "winding") return winding_;
    if (key == "net_winding") return net_;
    return ComputeStyle::value(key);
  }

 private:
  double r_;
  Vec3 c_;
  std::vector<std::string> names_;
  double A_ = 0, B_ = 0, winding_ = 0, net_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "morphology2d", slender::Morphology2dCompute)
