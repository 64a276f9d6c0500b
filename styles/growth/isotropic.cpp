// Uniform isotropic in-plane growth (docs/models.md §6.9, (5.41)): G = g (1 + rate t) 1,
// with g a constant factor (sim:modify can change it) and t the scene time.
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class IsotropicGrowth : public GrowthStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("growth", name,
                "uniform isotropic in-plane growth G = factor (1 + rate t) (docs/models.md §6.9 "
                "(5.41))");
    s.real("factor", "constant growth factor; sim:modify can change it").def(1.0).positive();
    s.real("rate", "growth rate lambda (per time unit)").def(0.0);
    s.output("factor", "constant growth factor");
    s.output("rate", "growth rate (per time unit)");
    return s;
  }
  IsotropicGrowth(Context&, const ParamValues& p)
      : factor_(p.real("factor")), rate_(p.real("rate")) {}
  Eigen::Matrix3d tensor(const Vec3&, double t) const override {
    return factor_ * (1.0 + rate_ * t) * Eigen::Matrix3d::Identity();
  }
  bool time_dependent() const override { return rate_ != 0.0; }
  void modify(const RawParams& raw) override {
    RawParams full = raw;
    if (!full.count("factor")) full["factor"] = factor_;
    if (!full.count("rate")) full["rate"] = rate_;
    auto p = spec(style_name()).validate(full);
    factor_ = p.real("factor");
    rate_ = p.real("rate");
    bump();
  }
  double value(const std::string& key) const override {
    if (key == "factor") return factor_;
    if (key == "rate") return rate_;
    return GrowthStyle::value(key);
  }
  void save_state(StateMap& s) const override { s["factor"] = {factor_}; }
  void load_state(const StateMap& s) override {
    if (auto it = s.find("factor"); it != s.end() && !it->second.empty()) {
      factor_ = it->second[0];
      bump();
    }
  }

 private:
  double factor_, rate_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::GrowthStyle, "isotropic", slender::IsotropicGrowth)
