// Clamps degrees of freedom of a group: the masked components keep zero force and
// velocity, so every integrator leaves them where they are. For director-free wires
// a clamped rotation is the direction of the end edge, so `rotation = true` also
// clamps the chain neighbour of every chain end in the group.
#include "context.hpp"
#include "held_components.hpp"
#include "registry.hpp"

namespace slender {

class ClampFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name, "fix positions (some or all components) and end rotations of a group");
    s.string("group", "node group").required();
    s.string("components", "position components to fix, any of x, y, z").def(std::string("xyz"));
    s.boolean("rotation", "also clamp the end-edge direction of chain ends in the group")
        .def(false);
    s.output(
        "count",
        "number of nodes in the group (chain-end neighbours clamped for rotation not counted)");
    return s;
  }
  ClampFix(Context& sim, const ParamValues& p) {
    const int bits = held_component_bits(p.str("components"), "fix 'clamp'");
    auto nodes = sim.group(p.str("group"));
    auto& mask = sim.held_components();
    bits_ = bits;
    auto add = [&](int i) {
      mask[i] |= bits;
      clamped_.push_back(i);
    };
    for (int i : nodes) add(i);
    if (p.boolean("rotation")) {
      for (auto& c : sim.topology().chains) {
        if (c.closed) continue;
        for (int i : nodes) {
          if (i == c.nodes.front()) add(c.nodes[1]);
          if (i == c.nodes.back()) add(c.nodes[c.nodes.size() - 2]);
        }
      }
    }
    count_ = static_cast<int>(nodes.size());
  }
  // Clamped components start and stay at rest (kinematically driven nodes of other
  // fixes share the mask but keep their prescribed velocity).
  // The bits are (re)set here too: a clamp removed by sim:unfix clears its bits, and the
  // other clamps of the same nodes set theirs again before the next step.
  // holds components through the mask (the solver drops them); adds no energy
  bool add_hessian(Context&, Hessian&) const override { return true; }
  unsigned stages() const override { return kSetup; }
  void setup(Context& sim) override {
    auto& mask = *sim.held_components_if_any();
    for (int i : clamped_) {
      mask[i] |= bits_;
      for (int c = 0; c < 3; ++c)
        if (mask[i] & (1 << c) & bits_) sim.nodes().v[i][c] = 0.0;
    }
  }
  void detach(Context& sim) override {
    if (auto* mask = sim.held_components_if_any())
      for (int i : clamped_) (*mask)[i] &= ~bits_;
  }
  double value(const std::string& key) const override {
    if (key == "count") return count_;
    return FixStyle::value(key);
  }

 private:
  int count_ = 0, bits_ = 0;
  std::vector<int> clamped_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "clamp", slender::ClampFix)
