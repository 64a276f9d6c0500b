// Growth given by a deck function of the reference position and time (docs/models.md
// §6.2): sim:growth("g", "function", {fn = function(x, y, z, t) return g end}). The
// function returns a scalar (isotropic), four numbers (the in-plane tensor in world
// x, y) or nine. With time_dependent = true it is called again whenever the scene
// time changes (once per Gauss point: convenient, not fast).
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class FunctionGrowth : public GrowthStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("growth", name,
                "growth tensor from a deck function fn(x, y, z, t) of the reference position and "
                "time: a scalar, {gxx, gxy, gyx, gyy} or nine numbers");
    s.add("fn", ParamType::Function,
          "fn(x, y, z, t) of the reference position and time, returning a scalar (isotropic), "
          "{gxx, gxy, gyx, gyy} (in-plane) or nine numbers")
        .required();
    s.boolean("time_dependent", "re-evaluate whenever the time changes").def(false);
    return s;
  }
  FunctionGrowth(Context&, const ParamValues& p) : time_(p.boolean("time_dependent")) {}
  bool wants_function() const override { return true; }
  void set_function(Function f) override {
    f_ = std::move(f);
    bump();
  }
  Eigen::Matrix3d tensor(const Vec3& X, double t) const override {
    if (!f_) throw InputError("growth '" + id() + "': no function was given");
    return f_(X, t);
  }
  bool time_dependent() const override { return time_; }
  void modify(const RawParams&) override { bump(); }  // re-evaluate (the function may read globals)

 private:
  bool time_;
  Function f_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::GrowthStyle, "function", slender::FunctionGrowth)
