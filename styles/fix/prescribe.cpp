// Prescribed motion of a group (displacement control, docs/models.md §9.8): the held
// components of its nodes follow a rigid motion from their reference positions X,
//   x(lambda) = c + R(lambda angle, axis) (X - c) + lambda u,
// with lambda the load factor (sim:continuation{load = id} walks it, sim:solve holds it),
// times a ramp from 0 to 1 over `duration` of a dynamic run. The fix measures the
// reaction, the force it exerts to keep the nodes on that path: minus the sum of the
// other styles' forces on the held components, read before the core zeroes them.
// With `frames`, the rod frames stored at the group's nodes (bond rod/cosserat keeps an
// edge's quaternion at its first node) turn with the same rotation and are held too:
// q(lambda) = r(lambda angle, axis) o Q, an end twisted by a prescribed angle.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "context.hpp"
#include "held_components.hpp"
#include "quaternion_rod.hpp"
#include "registry.hpp"

namespace slender {

class PrescribeFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name,
                "prescribed displacement and rotation of a group (displacement control): its "
                "held components follow c + R(lambda angle) (X - c) + lambda u");
    s.string("group", "node group").required();
    s.vector("displacement", "displacement u of every node of the group at load factor 1")
        .def(std::vector<double>{0, 0, 0})
        .length(2, 3);
    s.real("angle", "rotation angle (radians) about `axis` through `center` at load factor 1")
        .def(0.0);
    s.vector("axis", "rotation axis (in 2D the z axis)")
        .def(std::vector<double>{0, 0, 1})
        .length(3, 3);
    s.vector("center", "a point on the rotation axis")
        .def(std::vector<double>{0, 0, 0})
        .length(2, 3);
    s.string("components", "position components held on the path, any of x, y, z")
        .def(std::string("xyz"));
    s.boolean("frames",
              "also turn and hold the rod frames stored at the group's nodes (rod/cosserat: "
              "an edge's frame sits at its first node, so a chain end's group names its last "
              "two nodes): an end twisted by `angle` about its axis")
        .def(false);
    s.real("duration",
           "dynamic runs: the motion ramps smoothly (3 tau^2 - 2 tau^3) from 0 to the load "
           "factor over this time from when the fix was added (0: at once; leave 0 for "
           "static solves, whose clock stands)")
        .def(0.0)
        .nonnegative();
    s.output("reaction_x", "x component of the force the fix exerts on the group (the support's)");
    s.output("reaction_y", "y component of the reaction");
    s.output("reaction_z", "z component of the reaction");
    s.output("factor", "the motion's factor now: load factor times the ramp");
    s.output("count", "number of nodes in the group");
    return s;
  }
  PrescribeFix(Context& sim, const ParamValues& p)
      : group_(p.str("group")),
        u_(p.vec3("displacement")),
        angle_(p.real("angle")),
        axis_(p.vec3("axis")),
        center_(p.vec3("center")),
        duration_(p.real("duration")),
        t0_(sim.time()),
        frames_(p.boolean("frames")),
        ctx_(&sim) {
    bits_ = held_component_bits(p.str("components"), "fix 'prescribe'");
    if (angle_ != 0.0 && !(axis_.norm() > 0))
      throw InputError("fix 'prescribe': a rotation needs a nonzero axis");
    if (axis_.norm() > 0) axis_.normalize();
    if (sim.dimension() == 2 && angle_ != 0.0 && axis_.head<2>().norm() > 1e-12)
      throw InputError("fix 'prescribe': a 2D rotation turns about the z axis (axis = {0, 0, 1})");
    nodes_ = sim.group(group_);
    if (nodes_.empty()) throw InputError("fix 'prescribe': group '" + group_ + "' is empty");
    for (int i : nodes_) ref_.push_back(sim.nodes().x[i]);
    hold(sim);
  }
  // holds components through the mask (the solver drops them); adds no energy
  bool add_hessian(Context&, Hessian&) const override { return true; }
  unsigned stages() const override { return kSetup | kPostForce | kEndOfStep; }
  // reads the other styles' forces before the core zeroes the held components
  int priority() const override { return kMeasuresForces; }
  void setup(Context& sim) override {
    hold(sim);
    if (frames_ && !rod_) {
      for (auto& c : sim.extra_coordinates())
        if (c->name == "rod.q") rod_ = c.get();
      if (!rod_)
        throw InputError(
            "fix 'prescribe': frames = true needs a rod with frames (bond "
            "rod/cosserat)");
      // the rod gave its edges their frames in its setup, before this one (bonds are set up
      // before fixes): the reference frames are those, taken once (a checkpoint brings its own)
      if (ref_q_.empty())
        for (int i : nodes_) ref_q_.push_back((*rod_->q)[i]);
    }
    if (rod_)
      for (int i : nodes_) (*rod_->fixed)[i] = 1;
    place(sim, sim.time(), false);
  }
  void detach(Context& sim) override {
    if (auto* mask = sim.held_components_if_any())
      for (int i : nodes_) (*mask)[i] &= ~bits_;
    if (rod_)
      for (int i : nodes_) (*rod_->fixed)[i] = 0;
  }
  // The nodes move at once: a continuation evaluates the forces right after (bonds and
  // pairs run before this fix, so a move at post_force would come one evaluation late).
  bool set_continuation_parameter(double lambda) override {
    load_factor_ = lambda;
    place(*ctx_, ctx_->time(), false);
    return true;
  }
  double post_force(Context& sim) override {
    if (!placed_) place(sim, sim.time(), false);
    Vec3 r = Vec3::Zero();
    auto& f = sim.nodes().f;
    for (int i : nodes_)
      for (int c = 0; c < 3; ++c)
        if (bits_ & (1 << c)) r[c] -= f[i][c];
    reaction_ = r;
    return 0.0;
  }
  void end_of_step(Context& sim) override { place(sim, sim.time() + sim.dt(), true); }
  void save_state(StateMap& st) const override {
    st["t0"] = {t0_};
    st["load_factor"] = {load_factor_};
    std::vector<double> q;
    for (const Vec4& r : ref_q_) q.insert(q.end(), {r[0], r[1], r[2], r[3]});
    st["ref_frames"] = q;
  }
  void load_state(const StateMap& st) override {
    t0_ = saved_array(st, "t0", 1)[0];
    load_factor_ = saved_array(st, "load_factor", 1)[0];
    if (auto it = st.find("ref_frames"); it != st.end() && it->second.size() == 4 * nodes_.size()) {
      ref_q_.clear();
      for (size_t k = 0; k + 3 < it->second.size(); k += 4)
        ref_q_.emplace_back(it->second[k], it->second[k + 1], it->second[k + 2], it->second[k + 3]);
    }
    placed_ = false;
  }
  double value(const std::string& key) const override {
    if (key == "reaction_x") return reaction_.x();
    if (key == "reaction_y") return reaction_.y();
    if (key == "reaction_z") return reaction_.z();
    if (key == "factor") return factor_;
    if (key == "count") return static_cast<double>(nodes_.size());
    return FixStyle::value(key);
  }

 private:
  void hold(Context& sim) {
    auto& mask = sim.held_components();
    for (int i : nodes_) mask[i] |= bits_;
  }
  // smoothstep 3 tau^2 - 2 tau^3: the driven nodes start and stop without a jerk (a jump
  // of their speed from rest would be a shock to the scene, and to the guard's energy test)
  double ramp(double t) const {
    if (!(duration_ > 0)) return 1.0;
    const double tau = std::clamp((t - t0_) / duration_, 0.0, 1.0);
    return tau * tau * (3.0 - 2.0 * tau);
  }
  // the reference frame k turned by s angle about the axis (scalar-first quaternions,
  // the world-frame rotation applied after the frame's own)
  Vec4 turned(size_t k, double s) const {
    const double h = 0.5 * s * angle_;
    const Vec3 a = std::sin(h) * axis_;
    return qrod::mul(Vec4(std::cos(h), a.x(), a.y(), a.z()), ref_q_[k]);
  }
  Vec3 target(size_t k, double s) const {
    const Eigen::AngleAxisd turn(s * angle_, axis_);
    return center_ + turn * (ref_[k] - center_) + s * u_;
  }
  // Puts the held components on the path at time t (a dynamic step calls end_of_step
  // before its clock advances: its state is the one at time + dt); with `moving` their
  // velocities follow the path (its change over the step), else they are at rest.
  void place(Context& sim, double t, bool moving) {
    auto& n = sim.nodes();
    factor_ = load_factor_ * ramp(t);
    const double before = load_factor_ * ramp(t - sim.dt());
    for (size_t k = 0; k < nodes_.size(); ++k) {
      const int i = nodes_[k];
      const Vec3 x = target(k, factor_);
      const Vec3 v =
          moving && sim.dt() > 0 ? Vec3((x - target(k, before)) / sim.dt()) : Vec3::Zero();
      for (int c = 0; c < 3; ++c)
        if (bits_ & (1 << c)) {
          n.x[i][c] = x[c];
          n.v[i][c] = v[c];
        }
      if (rod_ && k < ref_q_.size()) {
        const Vec4 q = turned(k, factor_);
        (*rod_->v)[i] =
            moving && sim.dt() > 0 ? Vec4((q - turned(k, before)) / sim.dt()) : Vec4::Zero();
        (*rod_->q)[i] = q;
      }
    }
    placed_ = true;
  }

  std::string group_;
  std::vector<int> nodes_;
  std::vector<Vec3> ref_;
  Vec3 u_;
  double angle_;
  Vec3 axis_, center_;
  double duration_, t0_;
  bool frames_;
  Coordinates* rod_ = nullptr;  // the frames turned with the group (frames = true)
  std::vector<Vec4> ref_q_;     // their reference quaternions
  int bits_ = 0;
  double load_factor_ = 1.0, factor_ = 0.0;
  bool placed_ = false;
  Context* ctx_;  // the simulation's context, which outlives its styles
  Vec3 reaction_ = Vec3::Zero();
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "prescribe", slender::PrescribeFix)
