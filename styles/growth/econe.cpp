// E-cone growth (docs/models.md §6.9, (5.37)): circumferential growth about an axis,
// G = e_r (x) e_r + g e_phi (x) e_phi + e_z (x) e_z with g = 1 + phi_e / (2 pi), so a
// circle of radius r grows to the length (2 pi + phi_e) r. The excess angle phi_e is
// ramped by the deck with sim:modify(id, {phi_e = ...}).
#include <Eigen/Geometry>
#include <cmath>

#include "context.hpp"
#include "registry.hpp"

namespace slender {

class EconeGrowth : public GrowthStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("growth", name,
                "e-cone law: circumferential growth g = 1 + phi_e/(2 pi) about an axis "
                "(docs/models.md §6.9, (5.37))");
    s.real("phi_e",
           "excess angle (radians); sim:modify can change it, sim:continuation{load = id} "
           "walks it")
        .def(0.0)
        .min(-2 * M_PI);
    s.vector("center", "a point on the axis").def(std::vector<double>{0, 0, 0}).length(3, 3);
    s.vector("axis", "direction of the axis (the disc normal)")
        .def(std::vector<double>{0, 0, 1})
        .length(3, 3);
    s.output("phi_e", "excess angle phi_e (radians)");
    return s;
  }
  EconeGrowth(Context&, const ParamValues& p) { read(p); }
  void read(const ParamValues& p) {
    phi_e_ = p.real("phi_e");
    c_ = p.vec3("center");
    z_ = p.vec3("axis");
    if (z_.norm() == 0) throw InputError("growth 'econe': axis must be non-zero");
    z_.normalize();
  }
  Eigen::Matrix3d tensor(const Vec3& X, double) const override {
    Vec3 r = X - c_;
    r -= r.dot(z_) * z_;
    const double g = 1.0 + phi_e_ / (2 * M_PI);
    if (r.norm() < 1e-14) return std::sqrt(g) * Eigen::Matrix3d::Identity();  // apex: no direction
    const Vec3 er = r.normalized(), ep = z_.cross(er);
    return er * er.transpose() + g * ep * ep.transpose() + z_ * z_.transpose();
  }
  void modify(const RawParams& raw) override {
    RawParams full = raw;
    if (!full.count("phi_e")) full["phi_e"] = phi_e_;
    if (!full.count("center")) full["center"] = std::vector<double>{c_.x(), c_.y(), c_.z()};
    if (!full.count("axis")) full["axis"] = std::vector<double>{z_.x(), z_.y(), z_.z()};
    read(spec(style_name()).validate(full));
    bump();
  }
  // sim:continuation{load = id} walks phi_e (docs/models.md §9.4): the e-cone's branches
  // and their stability in the excess angle
  bool set_continuation_parameter(double lambda) override {
    if (lambda < -2 * M_PI) return false;
    phi_e_ = lambda;
    bump();
    return true;
  }
  double value(const std::string& key) const override {
    if (key == "phi_e") return phi_e_;
    return GrowthStyle::value(key);
  }
  void save_state(StateMap& s) const override { s["phi_e"] = {phi_e_}; }
  void load_state(const StateMap& s) override {
    if (auto it = s.find("phi_e"); it != s.end() && !it->second.empty()) {
      phi_e_ = it->second[0];
      bump();
    }
  }

 private:
  double phi_e_ = 0.0;
  Vec3 c_, z_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::GrowthStyle, "econe", slender::EconeGrowth)
