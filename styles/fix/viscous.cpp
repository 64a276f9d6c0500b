// Viscous damping F = -gamma v on a group (docs/models.md §2.1, "small viscous damping").
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class ViscousDampingFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name, "viscous damping force -gamma v on every node of a group");
    s.real("gamma", "drag coefficient (force per velocity)").required().nonnegative();
    s.string("group", "node group").def(std::string("all"));
    s.output("gamma", "drag coefficient gamma (force per velocity)");
    return s;
  }
  ViscousDampingFix(Context& sim, const ParamValues& p)
      : gamma_(p.real("gamma")), group_(p.str("group")) {
    sim.group(group_);
  }
  // -gamma v vanishes at rest and does not depend on the positions
  bool add_hessian(Context&, Hessian&) const override { return true; }
  unsigned stages() const override { return kPostForce | kSetup; }
  void setup(Context& sim) override { nodes_ = sim.group(group_); }
  double post_force(Context& sim) override {
    auto& f = sim.nodes().f;
    auto& v = sim.nodes().v;
    // each node is its own work item (threads.hpp)
    parallel_ranges(
        sim.threads(), nodes_.size(),
        [&](int, std::size_t begin, std::size_t end) {
          for (std::size_t k = begin; k < end; ++k) f[nodes_[k]] -= gamma_ * v[nodes_[k]];
        },
        kMinLightItemsPerThread);
    return 0.0;
  }
  // Explicit schemes need gamma dt / m below ~1; report gamma/m as a rate.
  double max_frequency(const Context& sim) const override {
    double mmin = 1e300;
    for (int i : sim.group(group_)) mmin = std::min(mmin, sim.nodes().mass[i]);
    return mmin < 1e300 ? gamma_ / mmin : 0.0;
  }
  void modify(const RawParams& raw) override {
    auto p = spec(style_name()).validate(raw);
    gamma_ = p.real("gamma");
  }
  double value(const std::string& key) const override {
    if (key == "gamma") return gamma_;
    return FixStyle::value(key);
  }

 private:
  double gamma_;
  std::string group_;
  std::vector<int> nodes_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "damping/viscous", slender::ViscousDampingFix)
