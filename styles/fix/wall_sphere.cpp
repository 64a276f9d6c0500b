// Rigid spherical (3D) or circular (2D) wall: the contact law of docs/models.md §2.3
// (normal repulsion k delta^p, dashpot, stick-slip friction) against a fixed body.
// Overlap delta = |x - c| + d/2 - R (inside) or R + d/2 - |x - c| (outside). The
// friction history is a node property, allocated only when mu_static > 0.
#include <array>
#include <cmath>
#include <cstdio>

#include "contact_law.hpp"
#include "context.hpp"
#include "hessian.hpp"
#include "registry.hpp"

namespace slender {

class SphereWallFix : public FixStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("fix", name,
                "rigid spherical (3D) / circular (2D) wall: penalty normal force, dashpot, "
                "stick-slip friction (docs/models.md §2.3)");
    s.vector("center", "centre of the wall").def(std::vector<double>{0, 0, 0}).length(2, 3);
    s.real("radius", "wall radius R0").required().positive();
    s.real("shrink_rate",
           "the radius shrinks as R(t) = R0 / (1 + rate t) (docs/models.md §7.2 S-6: the "
           "confinement ratio then grows linearly in time)")
        .def(0.0)
        .nonnegative();
    ContactLaw::declare(s);
    s.real("diameter", "node (wire) diameter d: contact starts at |x-c| = R - d/2")
        .def(0.0)
        .nonnegative();
    s.string("side", "which side the nodes live on")
        .def(std::string("inside"))
        .choices({"inside", "outside"});
    s.string("group", "node group").def(std::string("all"));
    s.vector("openings",
             "polar angles (radians, in the xy plane) of holes in the wall, e.g. "
             "{0, math.pi} for two opposite injection channels")
        .def(std::vector<double>{});
    s.real("opening_width", "width of each hole along the wall (default: the diameter)")
        .nonnegative();
    s.output("force", "sum of the normal forces of the wall on the nodes");
    s.output("contacts", "number of nodes touching the wall");
    s.output("radius", "current wall radius R(t)");
    s.output("omega", "contact frequency measured at the last evaluation, sqrt(max_i k_i / m_i)");
    return s;
  }
  SphereWallFix(Context& sim, const ParamValues& p)
      : c_(p.vec3("center")),
        r_(p.real("radius")),
        r0_(p.real("radius")),
        rate_(p.real("shrink_rate")),
        d_(p.real("diameter")),
        law_(ContactLaw::from(
            p, p.real("diameter") > 0 ? p.real("diameter") : 0.01 * p.real("radius"))),
        inside_(p.str("side") == "inside"),
        group_(p.str("group")),
        openings_(p.vec("openings")),
        half_gap_(0.5 * (p.has("opening_width") ? p.real("opening_width") : p.real("diameter")) /
                  p.real("radius")) {
    sim.group(group_);
    dim_ = sim.dimension();
    if (sim.dimension() == 2) c_.z() = 0.0;
    if (inside_ && r0_ <= 0.5 * d_)
      throw InputError("wall: radius " + fmt(r0_) +
                       " is not larger than the wire's radius d/2 = " + fmt(0.5 * d_) +
                       ": no wire fits inside; give a larger radius or a smaller diameter");
  }
  unsigned stages() const override { return kPostForce | kSetup; }
  // The friction history is named after the fix id, known from attach() on.
  void attach(Context& sim) override { bind(sim); }
  void setup(Context& sim) override {
    nodes_ = sim.group(group_);
    bind(sim);
    if (sim.step() == 0) check_start(sim);
  }
  void bind(Context& sim) {
    if (law_.frictional() && !xi_) {
      xi_ = &sim.nodes().require<Vec3>("wall:" + id() + ".xi", Vec3::Zero());
      state_ = &sim.nodes().require<int>("wall:" + id() + ".state", 0);
    }
  }
  double post_force(Context& sim) override {
    if (law_.frictional() && !xi_) bind(sim);
    if (rate_ > 0) r_ = r0_ / (1 + rate_ * sim.time());
    auto& x = sim.nodes().x;
    auto& v = sim.nodes().v;
    auto& f = sim.nodes().f;
    const Property<int>* mask = sim.held_components_if_any();
    // below this squared distance from the centre a node is clear of the wall by more than
    // a part in 1e-9 of r, so the exact test below would reject it too
    const double clear = (r_ - 0.5 * d_) * (1.0 - 1e-9);
    const double clear2 = clear > 0 ? clear * clear : -1.0;
    // each node is one work item and touches only its own force and history
    struct alignas(64) Part {  // one cache line per thread: written at every contact
      double e = 0.0, total = 0.0;
      int contacts = 0;
    };
    std::array<Part, kMaxThreads> parts{};
    stiffness_.prepare(sim.threads(), sim.nodes().size());
    const int T = parallel_ranges(
        sim.threads(), nodes_.size(),
        [&](int tid, std::size_t begin, std::size_t end) {
          Part& part = parts[static_cast<std::size_t>(tid)];
          NodeStiffness::Part& stiff = stiffness_.part(tid);
          for (std::size_t k = begin; k < end; ++k) {
            const int i = nodes_[k];
            // fully kinematic nodes (clamped, or driven in an injection channel) feel
            // no wall: their forces are discarded and must not enter any measurement
            if (mask && (*mask)[i] == kMaskAll) continue;
            const Vec3 rel = x[i] - c_;
            // most nodes of a packing are well inside: skip them before the root
            if (inside_ && rel.squaredNorm() < clear2) {
              if (law_.frictional() && (*state_)[i]) (*state_)[i] = 0, (*xi_)[i].setZero();
              continue;
            }
            const double dist = rel.norm();
            const double delta = inside_ ? dist + 0.5 * d_ - r_ : r_ + 0.5 * d_ - dist;
            FrictionState st;
            if (law_.frictional()) {
              st.xi = (*xi_)[i];
              st.stick = (*state_)[i] & 1;
              st.active = (*state_)[i] & 2;
            }
            if (delta <= 0.0 || dist == 0.0 || in_opening(rel)) {
              if (law_.frictional()) (*state_)[i] = 0, (*xi_)[i].setZero();
              continue;
            }
            const Vec3 n = (inside_ ? -1.0 : 1.0) * rel / dist;  // pushes back into the domain
            double fn = 0.0, e_contact = 0.0;
            f[i] += law_.force(delta, n, v[i], sim.dt(), st, &fn, &e_contact);
            if (law_.frictional()) {
              (*xi_)[i] = st.xi;
              (*state_)[i] = (st.stick ? 1 : 0) | (st.active ? 2 : 0);
            }
            stiff.add(i, law_.contact_stiffness(delta, st));
            part.e += e_contact;
            part.total += fn;
            ++part.contacts;
          }
        },
        kMinLightItemsPerThread);
    double e = 0.0;
    total_ = 0.0;
    contacts_ = 0;
    for (int t = 0; t < T; ++t) {
      e += parts[static_cast<std::size_t>(t)].e;
      total_ += parts[static_cast<std::size_t>(t)].total;
      contacts_ += parts[static_cast<std::size_t>(t)].contacts;
    }
    stiffness_.finish(sim.nodes().mass);
    return e;
  }
  // The Hessian of the wall energy k/(p+1) delta^(p+1), delta the node's overlap with the
  // wall along its distance from the centre (docs/models.md §9.9): the tangent stiffness
  // along the radius, and the force over the distance across it (a node pressed into
  // the inside of a sphere is pushed inwards, which softens it sideways; outside the
  // other way). Friction's stick springs have no energy of the positions alone: none then.
  bool add_hessian(Context& sim, Hessian& H) const override {
    if (law_.frictional()) return false;
    const auto& x = sim.nodes().x;
    const Property<int>* mask = sim.held_components_if_any();
    const int dim = sim.dimension();
    for (const int i : nodes_) {
      if (mask && (*mask)[i] == kMaskAll) continue;
      const Vec3 rel = x[i] - c_;
      const double dist = rel.norm();
      const double delta = inside_ ? dist + 0.5 * d_ - r_ : r_ + 0.5 * d_ - dist;
      if (delta <= 0.0 || dist == 0.0 || in_opening(rel)) continue;
      const Vec3 n = rel / dist;
      const Eigen::Matrix3d nn = n * n.transpose();
      // E'(dist) = +-F(delta): inside the force points inwards (-n), so E grows with dist
      const double dE = (inside_ ? 1.0 : -1.0) * law_.elastic_force(delta);
      const Eigen::Matrix3d h =
          law_.tangent_stiffness(delta) * nn + (dE / dist) * (Eigen::Matrix3d::Identity() - nn);
      if (dim == 2)
        H.add(i, i, Eigen::Matrix2d(h.topLeftCorner<2, 2>()));
      else
        H.add(i, i, h);
    }
    return true;
  }
  double max_frequency(const Context& sim) const override {
    double mmin = 1e300;
    for (int i : sim.group(group_)) mmin = std::min(mmin, sim.nodes().mass[i]);
    if (mmin >= 1e300) return 0.0;
    // stiffness at a reference overlap of a tenth of a diameter (or 0.1% of R)
    const double dref = d_ > 0 ? 0.1 * d_ : 1e-3 * r_;
    const double k =
        law_.tangent_stiffness(dref) + (law_.frictional() ? law_.stick_stiffness : 0.0);
    return std::sqrt(k / mmin);
  }
  double measured_frequency() const override { return stiffness_.omega(); }
  double value(const std::string& key) const override {
    if (key == "omega") return stiffness_.omega();
    if (key == "radius") return r_;
    if (key == "force") return total_;
    if (key == "contacts") return contacts_;
    return FixStyle::value(key);
  }
  void save_state(StateMap& st) const override {
    save_measured(st, {total_, double(contacts_), stiffness_.omega()});
  }
  void load_state(const StateMap& st) override {
    if (auto* m = load_measured(st, 3)) {
      total_ = (*m)[0], contacts_ = saved_int((*m)[1]);
      stiffness_.set_omega((*m)[2]);
    } else if (auto* m2 = load_measured(st, 2)) {
      total_ = (*m2)[0], contacts_ = saved_int((*m2)[1]);
    }
  }

 private:
  static std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
  }
  // Before the first step: a free node wholly on the wrong side of the wall would be thrown
  // back with a force of the full overlap, and the guard would report it later as a torn edge.
  // Say it in the deck's words now. Held nodes (an injection channel) and nodes in an
  // opening may lie beyond the wall.
  void check_start(Context& sim) const {
    const auto& x = sim.nodes().x;
    const Property<int>* mask = sim.held_components_if_any();
    for (int i : nodes_) {
      if (mask && (*mask)[i] == kMaskAll) continue;
      const Vec3 rel = x[i] - c_;
      const double dist = rel.norm();
      // wholly beyond the surface: an overlap of more than the diameter (a deep contact
      // within one diameter is the wall's business)
      const bool wrong = inside_ ? dist > r_ + 0.5 * d_ : dist < r_ - 0.5 * d_;
      if (!wrong || in_opening(rel)) continue;
      std::string where = "node " + std::to_string(i + 1);
      for (auto& c : sim.topology().chains)
        for (std::size_t k = 0; k < c.nodes.size(); ++k)
          if (c.nodes[k] == i)
            where += " (chain '" + c.name + "', its node " + std::to_string(k + 1) + ")";
      throw InputError("fix '" + id() + "' (" + style_name() + "): " + where + " starts " +
                       (inside_ ? "outside" : "inside") + " the wall: " + fmt(dist) +
                       " from its centre, radius " + fmt(r_) + " (side = \"" +
                       (inside_ ? "inside" : "outside") +
                       "\"); move the wire, or give the wall openings where it enters");
    }
  }
  // 2D: the circle as it is now, broken at the openings; 3D: three great circles.
  std::vector<std::vector<Vec3>> outline() const override {
    constexpr int kPoints = 256;
    std::vector<std::vector<Vec3>> lines;
    auto at = [&](int k, int plane) -> Vec3 {
      const double a = 2 * M_PI * k / kPoints, u = r_ * std::cos(a), w = r_ * std::sin(a);
      Vec3 p = c_;
      if (plane == 0) {
        p.x() += u;
        p.y() += w;
      } else if (plane == 1) {
        p.x() += u;
        p.z() += w;
      } else {
        p.y() += u;
        p.z() += w;
      }
      return p;
    };
    if (dim_ == 3) {
      for (int plane = 0; plane < 3; ++plane) {
        lines.emplace_back();
        for (int k = 0; k <= kPoints; ++k) lines.back().push_back(at(k % kPoints, plane));
      }
      return lines;
    }
    // arcs between the openings, starting inside one (or anywhere if there is none)
    int first = 0;
    while (first < kPoints && !in_opening(at(first, 0) - c_)) ++first;
    if (first == kPoints) first = 0;
    std::vector<Vec3> arc;
    for (int k = 0; k <= kPoints; ++k) {
      const Vec3 p = at((first + k) % kPoints, 0);
      if (in_opening(p - c_)) {
        if (arc.size() > 1) lines.push_back(arc);
        arc.clear();
      } else {
        arc.push_back(p);
      }
    }
    if (arc.size() > 1) lines.push_back(arc);
    return lines;
  }
  // Holes in the wall, e.g. where injection channels enter the cavity.
  bool in_opening(const Vec3& rel) const {
    if (openings_.empty()) return false;
    const double a = std::atan2(rel.y(), rel.x());
    for (double o : openings_) {
      const double diff = std::remainder(a - o, 2 * M_PI);
      if (std::abs(diff) <= half_gap_) return true;
    }
    return false;
  }

  Vec3 c_;
  double r_, r0_, rate_, d_;
  ContactLaw law_;
  bool inside_;
  std::string group_;
  std::vector<double> openings_;
  double half_gap_;  // half the opening width, as an angle
  int dim_ = 3;
  std::vector<int> nodes_;
  Property<Vec3>* xi_ = nullptr;
  Property<int>* state_ = nullptr;
  double total_ = 0.0;
  int contacts_ = 0;
  NodeStiffness stiffness_;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::FixStyle, "wall/sphere", slender::SphereWallFix)
SLENDER_REGISTER_STYLE(slender::FixStyle, "wall/circle", slender::SphereWallFix)
