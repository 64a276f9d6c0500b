// A moment on the end of a 2D chain (docs/models.md §9.5): M acts on the angle theta of the
// chain's end edge, E = -M theta, so the end edge's two nodes get the force pair
// F = M dtheta/dx (perpendicular to the edge, |F| = M / |e|): a follower load that turns with
// the end. Conservative, with its exact Hessian; its load factor scales M
// (sim:continuation), e.g. to roll a clamped wire into a full circle at M = 2 pi EI / L.
#include <cmath>

#include "context.hpp"
#include "hessian.hpp"
#include "hinge2d.hpp"
#include "registry.hpp"

namespace slender {

class EndMomentFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name,
                "moment on the end edge of a 2D chain (a follower force pair, conservative, "
                "docs/models.md §9.5)");
    s.string("chain", "the chain").required();
    s.string("end", "which end: \"head\" (its last node) or \"tail\" (its first)")
        .def(std::string("head"));
    s.real("moment", "moment M (counter-clockwise positive; force times length)").required();
    s.output("moment", "moment at the last evaluation (M times the load factor)");
    s.output("angle", "angle of the end edge (radians, continuous over turns)");
    return s;
  }
  EndMomentFix(Context& sim, const ParamValues& p)
      : chain_(p.str("chain")), head_(p.str("end") == "head"), moment_(p.real("moment")) {
    if (sim.dimension() != 2)
      throw InputError("fix 'moment2d' needs a 2D simulation (dimension = 2)");
    if (p.str("end") != "head" && p.str("end") != "tail")
      throw InputError("fix 'moment2d': end must be \"head\" or \"tail\", got \"" + p.str("end") +
                       "\"");
    const Chain* c = sim.topology().find(chain_);
    if (!c) throw InputError("fix 'moment2d': no chain '" + chain_ + "'");
    if (c->n_nodes() < 2) throw InputError("fix 'moment2d': chain '" + chain_ + "' has one node");
    if (c->closed) throw InputError("fix 'moment2d': chain '" + chain_ + "' is closed: no end");
  }
  unsigned stages() const override { return kPostForce; }
  bool set_continuation_parameter(double lambda) override {
    factor_ = lambda;
    return true;
  }
  double post_force(Context& sim) override {
    int a, b;
    ends(sim, a, b);
    auto& x = sim.nodes().x;
    auto& f = sim.nodes().f;
    const Eigen::Vector2d e = (x[b] - x[a]).head<2>();
    const Eigen::Vector2d g = Eigen::Vector2d(-e.y(), e.x()) / e.squaredNorm();  // dtheta/dx_b
    const double M = factor_ * moment_;
    f[b].head<2>() += M * g;
    f[a].head<2>() -= M * g;
    // the angle continued from the last evaluation (the end may turn by many pi)
    const double raw = std::atan2(e.y(), e.x());
    if (!started_) {
      angle_ = raw;
      started_ = true;
    } else {
      angle_ += std::remainder(raw - std::remainder(angle_, 2 * M_PI), 2 * M_PI);
    }
    last_ = M;
    return -M * angle_;
  }
  // E = -M theta: H = -M d^2theta/dx^2, with the blocks of A(e) (docs/models.md §9.2)
  bool add_hessian(Context& sim, Hessian& H) const override {
    int a, b;
    ends(sim, a, b);
    const auto& x = sim.nodes().x;
    const Eigen::Matrix2d h = -factor_ * moment_ * edge_angle_hessian((x[b] - x[a]).head<2>());
    H.add(b, b, h);
    H.add(a, a, h);
    H.add_pair(a, b, Eigen::Matrix2d(-h));
    return true;
  }
  void modify(const RawParams& raw) override {
    RawParams merged = raw;
    if (!merged.count("chain")) merged["chain"] = chain_;
    if (!merged.count("end")) merged["end"] = std::string(head_ ? "head" : "tail");
    if (!merged.count("moment")) merged["moment"] = moment_;
    auto p = spec(style_name()).validate(merged);
    moment_ = p.real("moment");
  }
  void save_state(StateMap& st) const override {
    st["angle"] = {angle_, started_ ? 1.0 : 0.0, factor_};
  }
  void load_state(const StateMap& st) override {
    auto& s = saved_array(st, "angle", 3);
    angle_ = s[0];
    started_ = s[1] != 0.0;
    factor_ = s[2];
  }
  double value(const std::string& key) const override {
    if (key == "moment") return last_;
    if (key == "angle") return angle_;
    return FixStyle::value(key);
  }

 private:
  void ends(Context& sim, int& a, int& b) const {
    const Chain* c = sim.topology().find(chain_);
    if (!c) throw InputError("fix 'moment2d': chain '" + chain_ + "' is gone");
    const int n = c->n_nodes();
    a = head_ ? c->nodes[n - 2] : c->nodes[1];
    b = head_ ? c->nodes[n - 1] : c->nodes[0];
  }
  std::string chain_;
  bool head_;
  double moment_, factor_ = 1.0, angle_ = 0.0, last_ = 0.0;
  bool started_ = false;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "moment2d", slender::EndMomentFix)
