// Axis-aligned box lo <= x <= hi (z ignored in 2D).
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class BoxRegion : public RegionStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("region", name, "axis-aligned box lo <= x <= hi");
    s.vector("lo", "lower corner").required().length(2, 3);
    s.vector("hi", "upper corner").required().length(2, 3);
    s.boolean("bounds", "part of the domain: a node outside every bounding region stops the run")
        .def(false);
    return s;
  }
  BoxRegion(Context& sim, const ParamValues& p)
      : lo_(p.vec3("lo")), hi_(p.vec3("hi")), dim_(sim.dimension()) {
    set_bounds(p.boolean("bounds"));
    for (int c = 0; c < dim_; ++c)
      if (!(lo_[c] < hi_[c]))
        throw InputError("region style 'box': needs lo < hi in every component");
  }
  bool contains(const Vec3& x) const override {
    for (int c = 0; c < dim_; ++c)
      if (x[c] < lo_[c] || x[c] > hi_[c]) return false;
    return true;
  }

 private:
  Vec3 lo_, hi_;
  int dim_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::RegionStyle, "box", slender::BoxRegion)
