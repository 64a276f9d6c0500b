// Core radius R_C of an e-cone (docs/models.md §6.11, [C]), from the per-face densities of
// the shell against the reference radius r round the apex, by one of three criteria:
// - "energy" (default): outside the core the cone is developable, U_b ~ 1/r^2, and the
//   bending energy inside r grows as A ln(r / R_C); a least-squares fit of the
//   cumulative sum of U_b dA against ln r over plateau_min <= r <= plateau_max gives A
//   and R_C (the usual core radius of d-cone theory). Integral, hence insensitive to
//   how few faces sample the angular variation of U_b in a ring.
// The other two average the densities, area-weighted, over rings of r (the two readings
// §6.11 gives; both noisy on faceted rings, kept for comparison):
// - "curvature": outside the core the cone is developable and |kappa| ~ 1/r, so
//   q(r) = r sqrt(<U_b>) is flat; R_C is where q, walking in from its plateau (the
//   median of q over plateau_min <= r <= plateau_max), first falls below
//   (1 - fraction) of the plateau.
// - "stretching": walking out from the ring where <U_s> peaks, R_C is where it first
//   falls below `fraction` of the peak. The in-plane strain of the disclination grows
//   without bound towards the apex, so this peak, and R_C with it, shrinks with every
//   refinement of the core (docs/shells/README.md).
// Crossings are interpolated linearly between the mean radii of the two rings that
// bracket them. Reference radii: the e-cone law (§6.9) leaves radii unchanged and the
// rings do not move with the shape. Empty rings are skipped.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "registry.hpp"
#include "shell/trimesh.hpp"
#include "simulation.hpp"

namespace slender {

class CoreRadiusCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "core radius R_C of an e-cone: the bending energy inside r grows as A ln(r / R_C) "
                "outside the core (or ring-averaged criteria), in reference radii");
    s.string("mesh", "surface created by sim:mesh").required();
    s.string("shell", "id of the shell style whose Ub / Us it reads").def(std::string("koiter"));
    s.string("criterion",
             "energy: fit of the bending energy inside r against ln r; curvature: "
             "r |kappa| departs from its plateau; stretching: U_s falls below a "
             "fraction of its peak")
        .def(std::string("energy"))
        .choices({"energy", "curvature", "stretching"});
    s.vector("center", "apex position in the reference")
        .def(std::vector<double>{0, 0, 0})
        .length(3, 3);
    s.real("fraction",
           "curvature: relative departure from the plateau; stretching: fraction "
           "of the peak")
        .def(0.1)
        .positive()
        .max(0.999);
    s.real("plateau_min", "energy, curvature: inner radius of the developable range")
        .def(0.3)
        .positive();
    s.real("plateau_max", "energy, curvature: outer radius of the developable range")
        .def(0.6)
        .positive();
    s.real("ring_width", "width of the radial rings; 0: the shortest reference edge")
        .def(0.0)
        .nonnegative();
    s.output("radius", "core radius R_C by the chosen criterion, as a reference radius");
    s.output(
        "level",
        "energy: A of A ln(r / R_C); curvature: plateau of r |kappa|; stretching: peak of U_s");
    s.output("rings", "number of non-empty rings in the profile (0 with criterion energy)");
    return s;
  }
  CoreRadiusCompute(Simulation& sim, const ParamValues& p)
      : shell_(p.str("shell")),
        criterion_(p.str("criterion")),
        c_(p.vec3("center")),
        fraction_(p.real("fraction")),
        pmin_(p.real("plateau_min")),
        pmax_(p.real("plateau_max")) {
    const Surface* s = sim.topology().find_surface(p.str("mesh"));
    if (!s) throw InputError("compute 'core_radius': no mesh named '" + p.str("mesh") + "'");
    if (pmax_ <= pmin_)
      throw InputError("compute 'core_radius': plateau_max must exceed plateau_min");
    const auto& g = *s->mesh;
    width_ = p.real("ring_width") > 0 ? p.real("ring_width") : shell::reference_edges(g).min;
    // ring index and reference area of every real face, fixed for the run
    for (int t = 0; t < g.n_real_tris; ++t) {
      const auto& tri = g.mesh.tri[t];
      const Vec3 a = g.mesh.x[tri[0]], b = g.mesh.x[tri[1]], c = g.mesh.x[tri[2]];
      const Vec3 m = (a + b + c) / 3.0 - c_;
      const Vec3 e1 = b - a, e2 = c - a;
      const double r = std::hypot(m.x(), m.y());
      radius_.push_back(r);
      area_.push_back(0.5 * e1.cross(e2).norm());
      ring_.push_back(static_cast<int>(r / width_));
    }
    n_rings_ = ring_.empty() ? 0 : *std::max_element(ring_.begin(), ring_.end()) + 1;
    order_.resize(radius_.size());
    for (std::size_t t = 0; t < order_.size(); ++t) order_[t] = t;
    std::stable_sort(order_.begin(), order_.end(),
                     [&](std::size_t a, std::size_t b) { return radius_[a] < radius_[b]; });
  }
  void evaluate(Simulation& sim) override {
    const bool stretching = criterion_ == "stretching", curvature = criterion_ == "curvature";
    const std::string key = stretching ? "Us" : "Ub";
    Style* st = sim.find_style(shell_);
    const std::vector<double>* v = st ? st->face_values(key) : nullptr;
    if (!v || v->size() != radius_.size())
      throw InputError("compute 'core_radius': no per-face field '" + shell_ + "." + key +
                       "' for this mesh");
    if (!stretching && !curvature) return from_energy(*v);
    // area-weighted ring means of the density and of the radius
    std::vector<double> w(n_rings_, 0.0), u(n_rings_, 0.0), r(n_rings_, 0.0);
    for (std::size_t t = 0; t < radius_.size(); ++t) {
      const int k = ring_[t];
      w[k] += area_[t];
      u[k] += area_[t] * (*v)[t];
      r[k] += area_[t] * radius_[t];
    }
    prof_.clear();  // (mean radius, profile value), non-empty rings, outwards
    for (int k = 0; k < n_rings_; ++k)
      if (w[k] > 0) {
        const double rk = r[k] / w[k], uk = u[k] / w[k];
        prof_.push_back({rk, curvature ? rk * std::sqrt(std::max(uk, 0.0)) : uk});
      }
    radius_c_ = level_ = 0;
    if (prof_.empty()) return;
    if (curvature)
      from_plateau();
    else
      from_peak();
  }
  double value(const std::string& key) const override {
    if (key == "radius") return radius_c_;
    // energy: A of A ln(r / R_C); curvature: the plateau of r |kappa|; stretching: the peak of U_s
    if (key == "level") return level_;
    if (key == "rings") return static_cast<double>(prof_.size());
    return ComputeStyle::value(key);
  }

 private:
  // linear interpolation of the radius where the profile crosses `cut` between rings a, b
  double crossing(std::size_t a, std::size_t b, double cut) const {
    const auto [r0, u0] = prof_[a];
    const auto [r1, u1] = prof_[b];
    return u0 == u1 ? r1 : r0 + (r1 - r0) * (u0 - cut) / (u0 - u1);
  }
  void from_energy(const std::vector<double>& ub) {
    prof_.clear();
    double e = 0, n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t t : order_) {
      e += area_[t] * ub[t];
      const double r = radius_[t];
      if (r < pmin_ || r > pmax_) continue;
      const double x = std::log(r);
      n += 1;
      sx += x;
      sy += e;
      sxx += x * x;
      sxy += x * e;
    }
    if (n < 2 || n * sxx - sx * sx <= 0)
      throw InputError(
          "compute 'core_radius': fewer than two faces between plateau_min and "
          "plateau_max");
    const double a = (n * sxy - sx * sy) / (n * sxx - sx * sx), b = (sy - a * sx) / n;
    level_ = a;
    radius_c_ = a > 0 ? std::exp(-b / a) : 0.0;  // no growth of the energy with r: no cone
  }
  void from_plateau() {
    std::vector<double> q;
    std::size_t inner = prof_.size();  // first ring of the plateau
    for (std::size_t k = 0; k < prof_.size(); ++k)
      if (prof_[k].first >= pmin_ && prof_[k].first <= pmax_) {
        q.push_back(prof_[k].second);
        inner = std::min(inner, k);
      }
    if (q.empty())
      throw InputError("compute 'core_radius': no ring between plateau_min and plateau_max");
    std::nth_element(q.begin(), q.begin() + q.size() / 2, q.end());
    level_ = q[q.size() / 2];
    const double cut = (1 - fraction_) * level_;
    radius_c_ = 0;  // never falls below the cut: no core resolved
    for (std::size_t k = inner; k-- > 0;)
      if (prof_[k].second < cut) {
        radius_c_ = crossing(k + 1, k, cut);
        break;
      }
  }
  void from_peak() {
    std::size_t kp = 0;
    for (std::size_t k = 1; k < prof_.size(); ++k)
      if (prof_[k].second > prof_[kp].second) kp = k;
    level_ = prof_[kp].second;
    const double cut = fraction_ * level_;
    radius_c_ = prof_.back().first;  // never falls below the cut: the whole surface is core
    for (std::size_t k = kp + 1; k < prof_.size(); ++k)
      if (prof_[k].second < cut) {
        radius_c_ = crossing(k - 1, k, cut);
        break;
      }
  }

  std::string shell_;
  std::string criterion_;
  Vec3 c_;
  double fraction_, pmin_, pmax_, width_ = 0;
  std::vector<double> radius_, area_;
  std::vector<int> ring_;
  std::vector<std::size_t> order_;  // faces by reference radius
  int n_rings_ = 0;
  std::vector<std::pair<double, double>> prof_;
  double radius_c_ = 0, level_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "core_radius", slender::CoreRadiusCompute)
