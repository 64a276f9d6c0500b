// Wire injection into a circular (2D) or spherical (3D) cavity through straight
// channels: along the x axis from one or both sides (docs/models.md §2.4), or through a
// nozzle in the sphere (§5.3). Nodes in a channel (beyond r - d/2 from the centre
// along the channel axis) are kinematic: their
// degrees of freedom are clamped and they move inward at the feed speed. When the
// outermost channel node has moved one rest length, a new node enters behind it;
// a node that passes the cavity's rim becomes free. The injection force is the
// axial force the feeder must exert on the channel nodes (minus the inward part of
// the internal forces on them), summed over the channels. Jamming: its moving
// average over the last `jam_time` time units exceeds `jam_force`, or it grows by
// `jam_growth` within a packing-density increase of `jam_dphi`; the run then ends
// cleanly. The window is a time, not a count of steps, so that the criterion means
// the same at every dt (and under an adaptive step).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>

#include "context.hpp"
#include "registry.hpp"

namespace slender {

class WireInjectionFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name,
                "push a wire into a circular or spherical cavity through channels along x or "
                "a nozzle; injection force, packing density, jamming stop (docs/models.md §2.4, "
                "§5.3)");
    s.string("chain",
             "the injected wire: straight along the channel axis, its pushed ends in "
             "the channels")
        .required();
    s.real("radius", "cavity radius r").required().positive();
    s.vector("center", "cavity centre").def(std::vector<double>{0, 0}).length(2, 3);
    s.string("channels",
             "opposite: both ends pushed along x; left / right: one end along x; nozzle: one end "
             "along 'direction'")
        .def(std::string("opposite"))
        .choices({"opposite", "left", "right", "nozzle"});
    s.vector("direction", "nozzle: inward direction of the feed (the nozzle sits at c - r dir)")
        .def(std::vector<double>{0, 0, -1})
        .length(2, 3);
    s.real("speed",
           "feed speed v_in (length per time unit) of each channel; sim:modify can set 0 "
           "to hold the wire (the force protocol of docs/models.md §2.4)")
        .required()
        .nonnegative();
    s.string("rotation",
             "a rod with frames (rod/cosserat): free = spin about the axis free in the channel "
             "(low torsion), held = the channel edges' frames are prescribed (high torsion, "
             "docs/models.md §4.5)")
        .def(std::string("free"))
        .choices({"free", "held"});
    s.real("diameter",
           "wire diameter d = 2a, for the packing density d L / (pi r^2) in 2D and "
           "L pi a^2 / (4/3 pi r^3) in 3D")
        .def(1.0)
        .positive();
    s.real("jam_force", "stop when the moving average of the injection force exceeds this")
        .def(std::numeric_limits<double>::infinity())
        .positive();
    s.real("jam_time",
           "time over which the injection force is averaged for the jamming tests (a time, "
           "not a step count: the test means the same at every dt); required with jam_force or "
           "jam_growth")
        .positive();
    s.real("jam_growth", "also stop when the averaged force grows by this factor ... (0: off)")
        .def(0.0)
        .nonnegative();
    s.real("jam_dphi", "... within this increase of the packing density").def(0.005).positive();
    s.real("max_phi", "stop at this packing density").def(1.0).positive();
    s.real("jam_min_phi",
           "the jamming tests apply only above this packing density (the straight wire's first "
           "hit of the far wall is not a jam)")
        .def(0.0)
        .nonnegative();
    s.real("perturb",
           "random transverse displacement (seeded) given to each node as the channel releases "
           "it: the wire entering a cavity is never perfectly straight, so it cannot hit the far "
           "wall exactly head-on")
        .def(0.0)
        .nonnegative();
    s.output("force",
             "injection force: axial force the feeder exerts on the channel nodes, summed over "
             "channels");
    s.output("force_avg", "injection force averaged over the last jam_time (time-weighted)");
    s.output("phi",
             "packing density: wire area (2D) or volume (3D) inside the cavity over the cavity's");
    s.output("jammed", "1 once the run stopped on a jam, else 0");
    s.output("injected", "wire length fed in since the start (rest lengths of the nodes added)");
    s.output("nodes_inside", "number of wire nodes inside the cavity");
    return s;
  }

  WireInjectionFix(Context& sim, const ParamValues& p)
      : chain_(p.str("chain")),
        r_(p.real("radius")),
        c_(p.vec3("center")),
        v_(p.real("speed")),
        d_(p.real("diameter")),
        jam_force_(p.real("jam_force")),
        window_(p.has("jam_time") ? p.real("jam_time") : 0.0),
        growth_(p.real("jam_growth")),
        dphi_(p.real("jam_dphi")),
        max_phi_(p.real("max_phi")),
        min_phi_(p.real("jam_min_phi")),
        hold_rotation_(p.str("rotation") == "held"),
        perturb_(p.real("perturb")) {
    dim_ = sim.dimension();
    if ((std::isfinite(jam_force_) || growth_ > 0) && !(window_ > 0))
      throw InputError(
          "fix style 'inject/wire': jam_force and jam_growth average the injection force over "
          "jam_time (time units); give jam_time, e.g. jam_time = 1000 * dt for the thesis' "
          "1000-step window at the reference dt");
    Chain* c = sim.topology().find(chain_);
    if (!c) throw InputError("fix style 'inject/wire': unknown chain '" + chain_ + "'");
    if (c->closed) throw InputError("fix style 'inject/wire': the chain must be open");
    auto& x = sim.nodes().x;
    const std::string ch = p.str("channels");
    // the pushed end of a channel with inward direction u: the chain end lying
    // farther out along -u
    auto end_for = [&](const Vec3& u) {
      return (x[c->nodes.front()] - c_).dot(u) < (x[c->nodes.back()] - c_).dot(u);
    };
    auto add = [&](const Vec3& u) { channels_.push_back(Channel{end_for(u), u}); };
    if (ch == "opposite" || ch == "left") add(Vec3(1, 0, 0));
    if (ch == "opposite" || ch == "right") add(Vec3(-1, 0, 0));
    if (ch == "nozzle") {
      Vec3 u = p.vec3("direction");
      if (dim_ == 2) u.z() = 0.0;
      if (u.norm() == 0.0) throw InputError("fix style 'inject/wire': direction must not be zero");
      add(u.normalized());
    }
    for (auto& k : channels_) {
      const int node = k.front ? c->nodes.front() : c->nodes.back();
      if (-(x[node] - c_).dot(k.u) < r_)
        throw InputError("fix style 'inject/wire': the chain's end node " +
                         std::to_string(node + 1) +
                         " must start in its channel, outside the cavity (at least r from the "
                         "centre along the channel)");
      k.anchor = x[node];
      k.rest = k.front ? c->rest_length.front() : c->rest_length.back();
      k.mass = sim.nodes().mass[node];
    }
    mask_ = &sim.held_components();
    // kinematic channel nodes: clamped degrees of freedom, constant inward velocity
    for (int i : c->nodes)
      if (in_channel(x[i])) drive(sim, i);
  }
  // measured after every other force fix, before the clamp zeroes the channel forces
  unsigned stages() const override { return kSetup | kPostForce | kEndOfStep; }
  // post_force measures the injection force from the complete forces: after every other fix
  int priority() const override { return kMeasuresForces; }
  void setup(Context& sim) override {
    mask_ = sim.held_components_if_any();
    if (hold_rotation_) {
      held_ = sim.prescribed_frames("rod.q");
      if (!held_)
        throw InputError(
            "fix style 'inject/wire': rotation = \"held\" needs a rod with frames "
            "(bond rod/cosserat)");
      for (int i : driven_) (*held_)[i] = 1;
    }
    // a changed feed speed (sim:modify) applies to the nodes already in the channels
    for (int i : driven_) sim.nodes().v[i] = v_ * driving(sim.nodes().x[i]).u;
  }
  void modify(const RawParams& raw) override {
    // only the feed speed may change between runs; the rest is the scene's geometry
    for (auto& kv : raw)
      if (kv.first != "speed")
        throw InputError("fix style 'inject/wire': modify accepts only 'speed', not '" + kv.first +
                         "'");
    RawParams full = raw;
    full["chain"] = chain_;
    full["radius"] = r_;
    v_ = spec(style_name()).validate(full).real("speed");
    recount_in_ = 0;  // the recount interval follows the feed speed
  }

  double post_force(Context& sim) override {
    // the feeder balances the inward component of the internal forces
    auto& f = sim.nodes().f;
    double total = 0.0;
    for (int i : driven_) total -= f[i].dot(driving(sim.nodes().x[i]).u);
    force_ = total;
    return 0.0;
  }

  void end_of_step(Context& sim) override {
    auto& x = sim.nodes().x;
    Chain* c = sim.topology().find(chain_);
    // the nodes this fix drives are free once they are clear of the rim
    for (size_t k = 0; k < driven_.size();) {
      const int i = driven_[k];
      if (!in_channel(x[i])) {
        (*mask_)[i] = 0;
        if (perturb_ > 0) kick(sim, i);
        if (held_) (*held_)[i] = 0;
        driven_[k] = driven_.back();
        driven_.pop_back();
      } else {
        ++k;
      }
    }
    // feed: a new node enters behind the outermost one
    for (auto& k : channels_) {
      const int outer = k.front ? c->nodes.front() : c->nodes.back();
      if (std::abs((x[outer] - k.anchor).dot(k.u)) >= k.rest) {
        Vec3 pos = x[outer] - k.u * k.rest;
        to_axis(pos, k.u);
        const int n = sim.grow_chain(chain_, k.front, pos, k.mass, k.rest);
        mask_ = sim.held_components_if_any();
        drive(sim, n);
        injected_ += k.rest;
        fed_ = true;
        c = sim.topology().find(chain_);
      }
    }
    // The packing density changes only as edge midpoints cross the rim, i.e. as the feed
    // advances: recount it (O(N)) each 1/50 of a rest length of feed and after a node
    // entered, not every step (it was 6 % of a crumpling run's time).
    recount_in_ -= sim.dt();
    if (recount_in_ <= 0 || fed_) {
      phi_ = packing(sim);
      const double rest = channels_.empty() ? d_ : channels_.front().rest;
      recount_in_ = v_ > 0 ? 0.02 * rest / v_ : 1000 * sim.dt();
      fed_ = false;
    }
    // time-weighted moving average of the injection force over the last jam_time
    history_.push_back({sim.dt(), force_});
    sum_ += sim.dt() * force_;
    span_ += sim.dt();
    while (history_.size() > 1 && span_ - history_.front().first >= window_) {
      sum_ -= history_.front().first * history_.front().second;
      span_ -= history_.front().first;
      history_.pop_front();
    }
    // the running sums drift by rounding over millions of steps: renew them now and then
    if (++since_renew_ >= 100000) {
      since_renew_ = 0;
      sum_ = span_ = 0.0;
      for (auto& [w, f] : history_) {
        sum_ += w * f;
        span_ += w;
      }
    }
    avg_ = span_ > 0 ? sum_ / span_ : force_;
    if (phi_ >= max_phi_)
      sim.request_stop("packing density reached max_phi = " + std::to_string(max_phi_));
    if (!(window_ > 0) || span_ < window_ * (1 - 1e-9) || phi_ < min_phi_) return;
    if (avg_ > jam_force_) {
      jammed_ = 1;
      sim.request_stop("jammed: injection force " + std::to_string(avg_) +
                       " > jam_force at phi = " + std::to_string(phi_));
    } else if (growth_ > 0) {
      marks_.push_back({phi_, avg_});
      while (!marks_.empty() && phi_ - marks_.front().first > dphi_) marks_.pop_front();
      if (marks_.front().second > 0 && avg_ > growth_ * marks_.front().second) {
        jammed_ = 1;
        sim.request_stop(
            "jammed: injection force grew " + std::to_string(avg_ / marks_.front().second) +
            "-fold within dphi = " + std::to_string(dphi_) + " at phi = " + std::to_string(phi_));
      }
    }
  }

  // toward max_phi when the deck set one (the jam itself cannot be foreseen)
  double stop_progress(std::string* what) const override {
    if (!(max_phi_ < 1.0)) return -1.0;
    if (what) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%s.phi = %g", id().c_str(), max_phi_);
      *what = buf;
    }
    return std::clamp(phi_ / max_phi_, 0.0, 1.0);
  }

  double value(const std::string& key) const override {
    if (key == "force") return force_;
    if (key == "force_avg") return avg_;
    if (key == "phi") return phi_;
    if (key == "jammed") return jammed_;
    if (key == "injected") return injected_;
    if (key == "nodes_inside") return inside_;
    return FixStyle::value(key);
  }
  void save_state(StateMap& st) const override {
    std::vector<double> ch, anchors;
    for (auto& k : channels_) {
      ch.push_back(k.anchor.x());
      anchors.insert(anchors.end(), {k.anchor.x(), k.anchor.y(), k.anchor.z()});
    }
    st["channels"] = ch;
    st["anchors"] = anchors;
    st["scalars"] = {force_,    avg_, phi_,  static_cast<double>(jammed_),
                     injected_, sum_, span_, recount_in_};
    // (dt, force) per step of the averaging window
    std::vector<double> h;
    for (auto& [w, f] : history_) h.insert(h.end(), {w, f});
    st["force_window"] = h;
    st["driven"] = std::vector<double>(driven_.begin(), driven_.end());
  }
  void load_state(const StateMap& st) override {
    if (st.count("anchors")) {
      auto& a = saved_array(st, "anchors");
      for (size_t i = 0; i < channels_.size() && 3 * i + 2 < a.size(); ++i)
        channels_[i].anchor = Vec3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
    } else {  // checkpoints of 2D runs before nozzles: the x coordinate on the axis
      auto& ch = saved_array(st, "channels");
      for (size_t i = 0; i < channels_.size() && i < ch.size(); ++i)
        channels_[i].anchor = Vec3(ch[i], c_.y(), 0.0);
    }
    auto& s = saved_array(st, "scalars");
    if (s.size() < 6)
      throw InputError("fix style 'inject/wire': the checkpoint's scalars hold " +
                       std::to_string(s.size()) + " values, at least 6 expected");
    force_ = s[0];
    avg_ = s[1];
    phi_ = s[2];
    jammed_ = saved_int(s[3]);
    injected_ = s[4];
    sum_ = s[5];
    if (!st.count("force_window") || s.size() < 7)
      throw InputError(
          "fix style 'inject/wire': this checkpoint was written by an older slender whose jamming "
          "window counted steps; it cannot be continued with the time-based jam_time");
    span_ = s[6];
    if (s.size() > 7) recount_in_ = s[7];
    auto& h = saved_array(st, "force_window");
    history_.clear();
    for (size_t i = 0; i + 1 < h.size(); i += 2) history_.push_back({h[i], h[i + 1]});
    auto& dr = saved_array(st, "driven");
    driven_.clear();
    bad_driven_ = false;
    for (double d : dr) {
      bad_driven_ = bad_driven_ || !(d >= 0 && d < 2147483647.0 && d == std::floor(d));
      driven_.push_back(bad_driven_ ? 0 : static_cast<int>(d));
    }
  }
  std::string check_loaded(const Context& sim) const override {
    const std::size_t n = sim.nodes().size();
    for (int i : driven_)
      if (bad_driven_ || static_cast<std::size_t>(i) >= n)
        return "a driven node index is not one of the " + std::to_string(n) + " nodes";
    if (!(span_ >= 0) || !std::isfinite(sum_) || !std::isfinite(force_) || !std::isfinite(avg_))
      return "the injection-force window holds NaN or a negative span";
    return "";
  }

 private:
  struct Channel {
    bool front;                  // the pushed end is the chain's first node (else its last)
    Vec3 u;                      // inward unit direction; the channel axis runs through the centre
    Vec3 anchor = Vec3::Zero();  // where the outermost node was when it entered
    double rest = 1, mass = 1;
  };
  // The channel a point lies in: beyond r - d/2 from the centre along its axis, so
  // that a released node never starts overlapping the cavity wall. Only sides with
  // a channel count: with channels = "left" the wire's other end is free.
  const Channel* channel_of(const Vec3& x) const {
    for (auto& k : channels_)
      if (-(x - c_).dot(k.u) >= r_ - 0.5 * d_) return &k;
    return nullptr;
  }
  bool in_channel(const Vec3& x) const { return channel_of(x) != nullptr; }
  // The channel a driven node belongs to: the one it lies farthest out along (a
  // driven node can pass r - d/2 within a step before it is released).
  const Channel& driving(const Vec3& x) const {
    const Channel* best = &channels_.front();
    for (auto& k : channels_)
      if (-(x - c_).dot(k.u) > -(x - c_).dot(best->u)) best = &k;
    return *best;
  }
  // a random displacement of amplitude perturb_ normal to the channel axis
  void kick(Context& sim, int i) {
    const Vec3 u = driving(sim.nodes().x[i]).u;
    std::uniform_real_distribution<double> r(-1.0, 1.0);
    Vec3 d(r(sim.rng()), r(sim.rng()), dim_ == 3 ? r(sim.rng()) : 0.0);
    d -= d.dot(u) * u;
    sim.nodes().x[i] += perturb_ * d;
  }
  // moves a point onto the channel axis (the channel holds the wire straight)
  void to_axis(Vec3& x, const Vec3& u) const {
    const Vec3 r = x - c_;
    x -= r - u * r.dot(u);
    if (dim_ == 2) x.z() = 0.0;
  }
  void drive(Context& sim, int i) {
    (*mask_)[i] = kMaskAll;
    if (hold_rotation_) {
      held_ = sim.prescribed_frames("rod.q");
      if (held_) (*held_)[i] = 1;
    }
    driven_.push_back(i);
    const Channel& k = driving(sim.nodes().x[i]);
    sim.nodes().v[i] = v_ * k.u;
    to_axis(sim.nodes().x[i], k.u);
  }
  double packing(Context& sim) {
    Chain* c = sim.topology().find(chain_);
    auto& x = sim.nodes().x;
    double length = 0.0;
    inside_ = 0;
    const double r2 = r_ * r_;  // squared distances: this runs every step over the wire
    auto inside = [&](const Vec3& p) {
      return (dim_ == 2 ? (p - c_).head<2>().squaredNorm() : (p - c_).squaredNorm()) < r2;
    };
    for (int e = 0; e < c->n_edges(); ++e)
      if (inside(0.5 * (x[c->edge_tail(e)] + x[c->edge_head(e)]))) length += c->rest_length[e];
    for (int i : c->nodes)
      if (inside(x[i])) ++inside_;
    if (dim_ == 2) return d_ * length / (M_PI * r_ * r_);
    // 3D (docs/models.md §5.4): phi = L pi a^2 / (4/3 pi R^3), a = d / 2
    return length * 0.25 * d_ * d_ / (4.0 / 3.0 * r_ * r_ * r_);
  }

  std::string chain_;
  double r_;
  Vec3 c_;
  double v_, d_, jam_force_;
  int dim_ = 2;
  double window_;  // jam_time; 0: no jamming tests
  double growth_, dphi_, max_phi_, min_phi_;
  bool hold_rotation_ = false;
  double perturb_ = 0.0;
  Property<int>* held_ = nullptr;  // rod.q.fixed: the frames the channel prescribes
  std::vector<Channel> channels_;
  std::vector<int> driven_;  // nodes this fix moves kinematically
  bool bad_driven_ = false;  // a checkpoint held a driven index that is not an index
  Property<int>* mask_ = nullptr;
  double force_ = 0, avg_ = 0, phi_ = 0, injected_ = 0, sum_ = 0, span_ = 0;
  long since_renew_ = 0;
  double recount_in_ = 0;  // time until the packing density is recounted
  bool fed_ = false;
  int jammed_ = 0, inside_ = 0;
  std::deque<std::pair<double, double>> history_;  // (dt, force) of the window's steps
  std::deque<std::pair<double, double>> marks_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "inject/wire", slender::WireInjectionFix)
