// Disc in the xy plane, |(x - c)_xy| <= R; in 3D an infinite cylinder along z.
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class CircleRegion : public RegionStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("region", name, "disc |(x-c)_xy| <= R (a z-aligned cylinder in 3D)");
    s.vector("center", "centre (x, y)").def(std::vector<double>{0, 0}).length(2, 3);
    s.real("radius", "radius").required().positive();
    s.boolean("bounds", "part of the domain: a node outside every bounding region stops the run")
        .def(false);
    return s;
  }
  CircleRegion(Context&, const ParamValues& p) : c_(p.vec3("center")), r_(p.real("radius")) {
    set_bounds(p.boolean("bounds"));
  }
  bool contains(const Vec3& x) const override {
    return (x - c_).head<2>().squaredNorm() <= r_ * r_;
  }

 private:
  Vec3 c_;
  double r_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::RegionStyle, "circle", slender::CircleRegion)
