// An out-of-tree style: fix "tether" pulls a group of nodes towards a point with a
// harmonic spring, E = k/2 |x - p|^2 per node. Built with slender_add_plugin (see
// CMakeLists.txt here) and loaded by a deck with slender.plugin("libtether.so"); it
// then registers, validates its parameters and documents itself (slender --help tether
// with SLENDER_PLUGIN_PATH set) exactly like a built-in style.
#include <cmath>

#include "context.hpp"
#include "registry.hpp"

namespace mystyles {

using namespace slender;

class TetherFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name, "harmonic tether of a group to a point, E = k/2 |x - p|^2 per node");
    s.string("group", "node group").required();
    s.vector("point", "anchor point").required().length(2, 3);
    s.real("k", "spring constant").required().positive();
    return s;
  }
  TetherFix(Context& sim, const ParamValues& p)
      : group_(p.str("group")), point_(p.vec3("point")), k_(p.real("k")) {
    sim.group(group_);  // an unknown group stops the deck at this line
  }
  unsigned stages() const override { return kPostForce; }
  double post_force(Context& sim) override {
    double e = 0;
    for (int i : sim.group(group_)) {
      const Vec3 d = sim.nodes().x[i] - point_;
      sim.nodes().f[i] -= k_ * d;
      e += 0.5 * k_ * d.squaredNorm();
    }
    return e;
  }
  double max_frequency(const Context& sim) const override {
    double m = 1e300;
    for (int i : sim.group(group_)) m = std::min(m, sim.nodes().mass[i]);
    return m < 1e300 ? std::sqrt(k_ / m) : 0.0;
  }

 private:
  std::string group_;
  Vec3 point_;
  double k_;
};

}  // namespace mystyles

SLENDER_REGISTER_STYLE(slender::FixStyle, "tether", mystyles::TetherFix)
SLENDER_PLUGIN_ENTRY()
