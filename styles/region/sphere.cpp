// Ball |x - c| <= R (in 2D, the disc in the xy plane).
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class SphereRegion : public RegionStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("region", name, "ball |x - c| <= R (a disc in 2D)");
    s.vector("center", "centre").def(std::vector<double>{0, 0, 0}).length(2, 3);
    s.real("radius", "radius").required().positive();
    s.boolean("bounds", "part of the domain: a node outside every bounding region stops the run")
        .def(false);
    return s;
  }
  SphereRegion(Context& sim, const ParamValues& p) : c_(p.vec3("center")), r_(p.real("radius")) {
    set_bounds(p.boolean("bounds"));
    if (sim.dimension() == 2) c_.z() = 0;
  }
  bool contains(const Vec3& x) const override { return (x - c_).squaredNorm() <= r_ * r_; }

 private:
  Vec3 c_;
  double r_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::RegionStyle, "sphere", slender::SphereRegion)
