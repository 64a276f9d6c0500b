// Radius of gyration of a group of nodes with their lumped masses (docs/models.md §5.4,
// (4.56)): R_g^2 = sum m_i |r_i - r_M|^2 / sum m_i, optionally only the nodes inside
// a sphere (the packed part of a wire, not the part still in the nozzle).
#include <cmath>

#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class GyrationCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "radius of gyration of a group (lumped masses), docs/models.md §5.4 (4.56)");
    s.string("group", "node group").def(std::string("all"));
    s.real("inside", "only nodes closer than this to 'center' (default: all of the group)")
        .positive();
    s.vector("center", "centre for 'inside'").def(std::vector<double>{0, 0, 0}).length(2, 3);
    s.output("rg", "mass-weighted radius of gyration of the selected nodes");
    s.output("rg2", "squared radius of gyration");
    s.output("nodes", "number of nodes selected (the group, within 'inside' of 'center' if given)");
    return s;
  }
  GyrationCompute(Simulation& sim, const ParamValues& p)
      : group_(p.str("group")),
        inside_(p.has("inside") ? p.real("inside") : 0.0),
        c_(p.vec3("center")) {
    sim.group(group_);  // an unknown group stops the deck here
  }
  void evaluate(Simulation& sim) override {
    auto& x = sim.nodes().x;
    auto& m = sim.nodes().mass;
    double M = 0.0;
    Vec3 rm = Vec3::Zero();
    std::vector<int> sel;
    for (int i : sim.group(group_))
      if (inside_ <= 0.0 || (x[i] - c_).norm() < inside_) sel.push_back(i);
    for (int i : sel) {
      M += m[i];
      rm += m[i] * x[i];
    }
    rg2_ = 0.0;
    n_ = static_cast<double>(sel.size());
    if (M <= 0.0) return;
    rm /= M;
    for (int i : sel) rg2_ += m[i] * (x[i] - rm).squaredNorm();
    rg2_ /= M;
  }
  double value(const std::string& key) const override {
    if (key == "rg") return std::sqrt(rg2_);
    if (key == "rg2") return rg2_;
    if (key == "nodes") return n_;
    return ComputeStyle::value(key);
  }

 private:
  std::string group_;
  double inside_;
  Vec3 c_;
  double rg2_ = 0.0, n_ = 0.0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "gyration", slender::GyrationCompute)
