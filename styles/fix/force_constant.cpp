// A constant (or linearly ramped) external force on every node of a group:
// F(t) = force + rate (t - t0), or node k's own F_k(t) = forces_k + rate (t - t0) from a
// table. Its potential is -F . (x - x_ref).
#include "context.hpp"
#include "registry.hpp"

namespace slender {

class ConstantForceFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name, "constant or linearly ramped external force on each node of a group");
    s.string("group", "node group").required();
    s.vector("force", "force vector on each node (or `forces`)").length(2, 3);
    s.vector("forces",
             "a table of per-node forces instead of `force`: dimension numbers per node of the "
             "group, in the group's order ({fx1, fy1, fz1, fx2, ...} in 3D)");
    s.vector("rate", "d force / dt, for slow load ramps")
        .def(std::vector<double>{0, 0, 0})
        .length(2, 3);
    s.output("fx",
             "x component of the force on each node at the last evaluation (with "
             "`forces`: of the total over the group)");
    s.output("fy", "y component of the force on each node (with `forces`: of the total)");
    s.output("fz", "z component of the force on each node (with `forces`: of the total)");
    s.output("magnitude", "magnitude of the force on each node (with `forces`: of the total)");
    return s;
  }
  ConstantForceFix(Context& sim, const ParamValues& p)
      : group_(p.str("group")),
        force_(p.has("force") ? p.vec3("force") : Vec3::Zero()),
        rate_(p.vec3("rate")),
        t0_(sim.time()),
        dim_(sim.dimension()) {
    nodes_ = sim.group(group_);
    read_table(p);
    check_plane();
    for (int i : nodes_) ref_.push_back(sim.nodes().x[i]);
  }
  // a force independent of the positions: no second derivative
  bool add_hessian(Context&, Hessian&) const override { return true; }
  unsigned stages() const override { return kPostForce | kSetup; }
  void setup(Context& sim) override {
    if (nodes_.size() != sim.group(group_).size()) {
      if (!table_.empty())
        throw InputError("fix style 'force/constant': group '" + group_ + "' now holds " +
                         std::to_string(sim.group(group_).size()) + " nodes, its `forces` table " +
                         std::to_string(table_.size()) + " (a table is per node of the group)");
      nodes_ = sim.group(group_);
      ref_.clear();
      for (int i : nodes_) ref_.push_back(sim.nodes().x[i]);
    }
  }
  Vec3 current(double t) const { return load_factor_ * (force_ + rate_ * (t - t0_)); }
  bool set_continuation_parameter(double lambda) override {
    load_factor_ = lambda;
    return true;
  }
  double post_force(Context& sim) override {
    const Vec3 F = current(sim.time());
    auto& f = sim.nodes().f;
    auto& x = sim.nodes().x;
    double e = 0.0;
    if (!table_.empty()) {
      last_.setZero();
      for (size_t k = 0; k < nodes_.size(); ++k) {
        const Vec3 Fk = load_factor_ * table_[k] + F;  // F: the ramp alone here
        f[nodes_[k]] += Fk;
        e -= Fk.dot(x[nodes_[k]] - ref_[k]);
        last_ += Fk;
      }
      return e;
    }
    for (size_t k = 0; k < nodes_.size(); ++k) {
      f[nodes_[k]] += F;
      e -= F.dot(x[nodes_[k]] - ref_[k]);
    }
    last_ = F;
    return e;
  }
  void modify(const RawParams& raw) override {
    RawParams merged = raw;
    if (!merged.count("group")) merged["group"] = group_;
    if (!merged.count("force") && !merged.count("forces")) {
      if (table_.empty()) {
        merged["force"] = std::vector<double>{force_.x(), force_.y(), force_.z()};
      } else {
        std::vector<double> t;
        for (auto& v : table_)
          for (int c = 0; c < dim_; ++c) t.push_back(v[c]);
        merged["forces"] = t;
      }
    }
    auto p = spec(style_name()).validate(merged);
    force_ = p.has("force") ? p.vec3("force") : Vec3::Zero();
    rate_ = p.vec3("rate");
    read_table(p);
    check_plane();
  }
  void save_state(StateMap& st) const override {
    st["t0"] = {t0_};
    st["force"] = {force_.x(), force_.y(), force_.z()};
    st["rate"] = {rate_.x(), rate_.y(), rate_.z()};
    st["load_factor"] = {load_factor_};
    std::vector<double> t;
    for (auto& v : table_) t.insert(t.end(), {v.x(), v.y(), v.z()});
    st["forces"] = t;
    std::vector<double> r;
    for (auto& v : ref_) r.insert(r.end(), {v.x(), v.y(), v.z()});
    st["ref"] = r;
  }
  void load_state(const StateMap& st) override {
    t0_ = saved_array(st, "t0", 1)[0];
    auto& fo = saved_array(st, "force", 3);
    force_ = Vec3(fo[0], fo[1], fo[2]);
    auto& ra = saved_array(st, "rate", 3);
    rate_ = Vec3(ra[0], ra[1], ra[2]);
    // (checkpoints written before continuation existed have no load factor: 1)
    if (auto it = st.find("load_factor"); it != st.end() && !it->second.empty())
      load_factor_ = it->second[0];
    table_.clear();
    if (auto it = st.find("forces"); it != st.end())
      for (size_t i = 0; i + 2 < it->second.size(); i += 3)
        table_.emplace_back(it->second[i], it->second[i + 1], it->second[i + 2]);
    auto& r = saved_array(st, "ref");
    ref_.resize(r.size() / 3);
    for (size_t i = 0; i < ref_.size(); ++i) ref_[i] = Vec3(r[3 * i], r[3 * i + 1], r[3 * i + 2]);
  }
  double value(const std::string& key) const override {
    if (key == "fx") return last_.x();
    if (key == "fy") return last_.y();
    if (key == "fz") return last_.z();
    if (key == "magnitude") return last_.norm();
    return FixStyle::value(key);
  }

 private:
  // a 2D scene moves in the xy plane: a z component would be dropped without a word (a load
  // written {0, 0, -P} for "downwards" gave a tip deflection of 0)
  // exactly one of force and forces; a table holds dimension numbers per node of the group
  void read_table(const ParamValues& p) {
    if (p.has("force") == p.has("forces"))
      throw InputError(
          "fix style 'force/constant': give either `force` (one vector on every node of the "
          "group) or `forces` (a table of per-node forces), " +
          std::string(p.has("force") ? "not both" : "one of them"));
    table_.clear();
    if (!p.has("forces")) return;
    const auto& t = p.vec("forces");
    const size_t want = static_cast<size_t>(dim_) * nodes_.size();
    if (t.size() != want)
      throw InputError("fix style 'force/constant': `forces` holds " + std::to_string(t.size()) +
                       " numbers; group '" + group_ + "' has " + std::to_string(nodes_.size()) +
                       " nodes, so it needs " + std::to_string(want) + " (" + std::to_string(dim_) +
                       " per node, in the group's order)");
    for (size_t k = 0; k < nodes_.size(); ++k)
      table_.emplace_back(t[dim_ * k], t[dim_ * k + 1], dim_ == 3 ? t[dim_ * k + 2] : 0.0);
  }
  void check_plane() const {
    if (dim_ == 2 && (force_.z() != 0.0 || rate_.z() != 0.0))
      throw InputError(
          "fix style 'force/constant': force and rate have a z component in a 2D scene (dimension "
          "= 2), "
          "whose nodes move in the xy plane: give {fx, fy}");
  }
  std::string group_;
  Vec3 force_, rate_;
  double t0_;
  double load_factor_ = 1.0;  // lambda of a continuation (docs/models.md §9.4)
  int dim_ = 3;
  std::vector<int> nodes_;
  std::vector<Vec3> ref_;
  std::vector<Vec3> table_;  // per node of the group (`forces`); empty: `force` on every node
  Vec3 last_ = Vec3::Zero();
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "force/constant", slender::ConstantForceFix)
