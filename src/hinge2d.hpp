// Geometry of a 2D hinge (interior node m between nodes a and b), MODELS.md §2.1:
// the signed turning angle zeta = atan2(e0 x e1, e0 . e1) with e0 = x_m - x_a,
// e1 = x_b - x_m, its exact gradients dzeta/dx_b = z x e1/|e1|^2,
// dzeta/dx_a = z x e0/|e0|^2, dzeta/dx_m = -(both), with z x v = (-v_y, v_x).
// Shared by the bending styles and the observables that measure curvature.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "nodes.hpp"

namespace slender {

struct Hinge2d {
  double zeta;
  Eigen::Vector2d ga, gb;  // dzeta/dx_a and dzeta/dx_b

  Hinge2d(const Vec3& xa, const Vec3& xm, const Vec3& xb) {
    const Eigen::Vector2d e0 = (xm - xa).head<2>(), e1 = (xb - xm).head<2>();
    zeta = std::atan2(e0.x() * e1.y() - e0.y() * e1.x(), e0.dot(e1));
    gb = Eigen::Vector2d(-e1.y(), e1.x()) / e1.squaredNorm();
    ga = Eigen::Vector2d(-e0.y(), e0.x()) / e0.squaredNorm();
  }
  // Nodal forces of a generalised moment conjugate to zeta: F_j = -M dzeta/dx_j.
  void apply(std::vector<Vec3>& f, int a, int m, int b, double M) const {
    f[b].head<2>() -= M * gb;
    f[a].head<2>() -= M * ga;
    f[m].head<2>() += M * (ga + gb);
  }
  // dzeta/dt = sum_j dzeta/dx_j . v_j
  double rate(const std::vector<Vec3>& v, int a, int m, int b) const {
    return gb.dot(v[b].head<2>()) + ga.dot(v[a].head<2>()) - (ga + gb).dot(v[m].head<2>());
  }
};

}  // namespace slender
