// Geometry of a 2D hinge (interior node m between nodes a and b), docs/models.md §2.1:
// the signed turning angle zeta = atan2(e0 x e1, e0 . e1) with e0 = x_m - x_a,
// e1 = x_b - x_m, its exact gradients dzeta/dx_b = z x e1/|e1|^2,
// dzeta/dx_a = z x e0/|e0|^2, dzeta/dx_m = -(both), with z x v = (-v_y, v_x).
// Shared by the bending styles and the observables that measure curvature.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "context.hpp"
#include "hessian.hpp"
#include "nodes.hpp"
#include "params.hpp"
#include "threads.hpp"
#include "topology.hpp"

namespace slender {

// Per-node fields of a 2D bending style, for dumps and plots (off by default, and then
// nothing is allocated): bend.curvature, kappa = zeta / l0 at each interior node, and
// bend.energy, its bending energy. The end nodes of open chains read 0. Derived from the
// positions at every force evaluation, so not kept in checkpoints.
inline void declare_node_fields(ParamSpec& s) {
  s.boolean("node_fields",
            "keep each interior node's curvature zeta / l0 and bending energy in the node "
            "properties bend.curvature and bend.energy (for dumps; off: nothing allocated)")
      .def(false);
}
class HingeNodeFields {
 public:
  void bind(Context& sim, const ParamValues& p) {
    on_ = p.boolean("node_fields");
    rebind(sim);
  }
  void rebind(Context& sim) {
    if (!on_) return;
    const PropertyOptions derived{.restart = false, .dump = true};
    curvature_ = &sim.nodes().require<double>("bend.curvature", 0.0, derived);
    energy_ = &sim.nodes().require<double>("bend.energy", 0.0, derived);
  }
  bool on() const { return on_; }
  void clear() {
    if (!on_) return;
    for (auto& k : curvature_->values()) k = 0.0;
    for (auto& e : energy_->values()) e = 0.0;
  }
  // each hinge writes its own interior node: safe on threads
  void set(int node, double kappa, double energy) {
    if (!on_) return;
    (*curvature_)[node] = kappa;
    (*energy_)[node] = energy;
  }

 private:
  bool on_ = false;
  Property<double>* curvature_ = nullptr;
  Property<double>* energy_ = nullptr;
};

// The rest length hinge h of a chain stands for: the mean of its two edges (the curvature
// of a 2D wire is kappa = zeta / l0, docs/models.md §2.1).
inline double hinge_rest_length(const Chain& c, int h) {
  const int ne = c.n_edges();
  const int e_prev = c.closed ? (h - 1 + ne) % ne : h;
  const int e_next = c.closed ? h : h + 1;
  return 0.5 * (c.rest_length[e_prev] + c.rest_length[e_next]);
}

// atan t for |t| <= 0.2 by its series t - t^3/3 + t^5/5 - ..., summed to t^25: exact to
// rounding there (the next term is below 1e-18 t). Estrin's scheme keeps the dependency
// chain short.
inline double atan_series(double t) {
  constexpr auto a = [] {
    std::array<double, 13> coef{};  // (-1)^k / (2k + 1)
    for (int k = 0; k < 13; ++k) coef[k] = (k % 2 ? -1.0 : 1.0) / (2 * k + 1);
    return coef;
  }();
  const double x = t * t, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  const double q0 = (a[0] + a[1] * x) + (a[2] + a[3] * x) * x2;
  const double q1 = (a[4] + a[5] * x) + (a[6] + a[7] * x) * x2;
  const double q2 = (a[8] + a[9] * x) + (a[10] + a[11] * x) * x2;
  return t * ((q0 + q1 * x4) + (q2 + a[12] * x4) * x8);
}
inline const double kAtanOf04 = std::atan(0.4), kAtanOf08 = std::atan(0.8);

// atan2(c, d) for a hinge's turning angle. Turns up to atan 0.2 (11 degrees) take the series
// directly; up to 45 degrees, atan t = atan a + atan((t - a) / (1 + a t)) with a = 0.4 or
// 0.8 brings the argument back within 0.2. Within 4 ulp of std::atan2 and several times
// faster, where std::atan2 had become the largest single cost of the 2D scenes (and, with
// the series to 11 degrees only, still 4 % of a crumpling run at f = 100, whose loops turn
// by more). Elsewhere std::atan2.
inline double hinge_angle(double c, double d) {
  if (d > 0.0) {
    const double ac = std::abs(c);
    if (ac <= 0.2 * d) return atan_series(c / d);
    if (ac <= d) {
      const double t = ac / d;
      const bool low = t <= 0.6;
      const double a = low ? 0.4 : 0.8;
      const double r = (low ? kAtanOf04 : kAtanOf08) + atan_series((t - a) / (1.0 + a * t));
      return c < 0 ? -r : r;
    }
  }
  return std::atan2(c, d);
}

// d/de (z x e / |e|^2) = z x (I - 2 e e^T / |e|^2) / |e|^2: the second derivative of the
// angle of an edge e (docs/models.md §9.2); symmetric (a rotation times a reflection).
inline Eigen::Matrix2d edge_angle_hessian(const Eigen::Vector2d& e) {
  const double l2 = e.squaredNorm();
  Eigen::Matrix2d J;
  J << 0.0, -1.0, 1.0, 0.0;
  return J * (Eigen::Matrix2d::Identity() - 2.0 * e * e.transpose() / l2) / l2;
}

struct Hinge2d {
  double zeta;
  Eigen::Vector2d ga, gb;  // dzeta/dx_a and dzeta/dx_b

  Hinge2d(const Vec3& xa, const Vec3& xm, const Vec3& xb) {
    const Eigen::Vector2d e0 = (xm - xa).head<2>(), e1 = (xb - xm).head<2>();
    zeta = hinge_angle(e0.x() * e1.y() - e0.y() * e1.x(), e0.dot(e1));
    gb = Eigen::Vector2d(-e1.y(), e1.x()) / e1.squaredNorm();
    ga = Eigen::Vector2d(-e0.y(), e0.x()) / e0.squaredNorm();
  }
  // Nodal forces of a generalised moment conjugate to zeta: F_j = -M dzeta/dx_j.
  void apply(Vec3* f, int a, int m, int b, double M) const {
    f[b].head<2>() -= M * gb;
    f[a].head<2>() -= M * ga;
    f[m].head<2>() += M * (ga + gb);
  }
  void apply(std::vector<Vec3>& f, int a, int m, int b, double M) const {
    apply(f.data(), a, m, b, M);
  }
  // The same through a chain kernel's sink, the hinge's first node at chain position p.
  void apply(ChainForces& f, long p, int a, int m, int b, double M) const {
    f.at(p + 2, b).head<2>() -= M * gb;
    f.at(p, a).head<2>() -= M * ga;
    f.at(p + 1, m).head<2>() += M * (ga + gb);
  }
  // Second derivatives of a hinge energy E(zeta) into H (docs/models.md §9.2):
  // E'' g g^T + E' d^2zeta/dx^2, with stiffness = E''(zeta) and moment = E'(zeta). With
  // A(e) = z x (I - 2 e e^T / |e|^2) / |e|^2, the derivative of z x e / |e|^2 (symmetric),
  // the blocks of d^2zeta/dx^2 are aa = -A0, am = A0, mm = A1 - A0, mb = -A1, bb = A1.
  void add_hessian(Hessian& H, const Vec3& xa, const Vec3& xm, const Vec3& xb, int a, int m, int b,
                   double stiffness, double moment) const {
    const Eigen::Matrix2d A0 = edge_angle_hessian((xm - xa).head<2>()),
                          A1 = edge_angle_hessian((xb - xm).head<2>());
    const Eigen::Vector2d gm = -(ga + gb);
    H.add(a, a, Eigen::Matrix2d(stiffness * ga * ga.transpose() - moment * A0));
    H.add(m, m, Eigen::Matrix2d(stiffness * gm * gm.transpose() + moment * (A1 - A0)));
    H.add(b, b, Eigen::Matrix2d(stiffness * gb * gb.transpose() + moment * A1));
    H.add_pair(a, m, Eigen::Matrix2d(stiffness * ga * gm.transpose() + moment * A0));
    H.add_pair(m, b, Eigen::Matrix2d(stiffness * gm * gb.transpose() - moment * A1));
    H.add_pair(a, b, Eigen::Matrix2d(stiffness * ga * gb.transpose()));
  }
  // dzeta/dt = sum_j dzeta/dx_j . v_j
  double rate(const std::vector<Vec3>& v, int a, int m, int b) const {
    return gb.dot(v[b].head<2>()) + ga.dot(v[a].head<2>()) - (ga + gb).dot(v[m].head<2>());
  }
};

}  // namespace slender
