// Rigid spherical (3D) or circular (2D) wall with a penalty normal force.
// Overlap delta = |x - c| + d/2 - R (inside) or R + d/2 - |x - c| (outside);
// F = k delta^p along the wall normal, E = k delta^(p+1) / (p+1). p = 2 is the
// quadratic law of MODELS.md §2.3; friction comes with the contact styles.
#include <cmath>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class SphereWallFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name,
                "rigid spherical (3D) / circular (2D) wall with a penalty normal force");
    s.vector("center", "centre of the wall").def(std::vector<double>{0, 0, 0}).length(2, 3);
    s.real("radius", "wall radius").required().positive();
    s.real("stiffness", "penalty stiffness k").required().positive();
    s.real("exponent", "force law F = k delta^p: 1 linear, 2 quadratic (MODELS.md §2.3)")
        .def(1.0)
        .min(1.0)
        .max(3.0);
    s.real("diameter", "node (wire) diameter d: contact starts at |x-c| = R - d/2")
        .def(0.0)
        .nonnegative();
    s.string("side", "which side the nodes live on")
        .def(std::string("inside"))
        .choices({"inside", "outside"});
    s.string("group", "node group").def(std::string("all"));
    return s;
  }
  SphereWallFix(Simulation& sim, const ParamValues& p)
      : c_(p.vec3("center")),
        r_(p.real("radius")),
        k_(p.real("stiffness")),
        p_(p.real("exponent")),
        d_(p.real("diameter")),
        inside_(p.str("side") == "inside"),
        group_(p.str("group")) {
    sim.group(group_);
    if (sim.dimension() == 2) c_.z() = 0.0;
  }
  unsigned stages() const override { return kPostForce | kSetup; }
  void setup(Simulation& sim) override { nodes_ = sim.group(group_); }
  double post_force(Simulation& sim) override {
    auto& x = sim.nodes().x;
    auto& f = sim.nodes().f;
    double e = 0.0;
    total_ = 0.0;
    contacts_ = 0;
    for (int i : nodes_) {
      Vec3 rel = x[i] - c_;
      const double dist = rel.norm();
      const double delta = inside_ ? dist + 0.5 * d_ - r_ : r_ + 0.5 * d_ - dist;
      if (delta <= 0.0 || dist == 0.0) continue;
      const Vec3 n = (inside_ ? -1.0 : 1.0) * rel / dist;  // pushes back into the domain
      const double mag = k_ * std::pow(delta, p_);
      f[i] += mag * n;
      e += k_ * std::pow(delta, p_ + 1.0) / (p_ + 1.0);
      total_ += mag;
      ++contacts_;
    }
    return e;
  }
  double max_frequency(const Simulation& sim) const override {
    double mmin = 1e300;
    for (int i : sim.group(group_)) mmin = std::min(mmin, sim.nodes().mass[i]);
    if (mmin >= 1e300) return 0.0;
    // stiffness dF/ddelta at a reference overlap of one diameter (or 1% of R)
    const double dref = d_ > 0 ? d_ : 0.01 * r_;
    const double kt = p_ * k_ * std::pow(dref, p_ - 1.0);
    return std::sqrt(kt / mmin);
  }
  std::vector<std::string> value_keys() const override { return {"force", "contacts"}; }
  double value(const std::string& key) const override {
    if (key == "force") return total_;
    if (key == "contacts") return contacts_;
    return FixStyle::value(key);
  }

 private:
  Vec3 c_;
  double r_, k_, p_, d_;
  bool inside_;
  std::string group_;
  std::vector<int> nodes_;
  double total_ = 0.0;
  int contacts_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "wall/sphere", slender::SphereWallFix)
SLENDER_REGISTER_STYLE(slender::FixStyle, "wall/circle", slender::SphereWallFix)
