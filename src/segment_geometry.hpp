// Geometry of two straight segments, shared by the 3D contact styles.
#pragma once

#include <algorithm>

#include "nodes.hpp"

namespace slender {

// Closest points x = p1 + s (q1 - p1), y = p2 + t (q2 - p2) of two segments.
// Parallel segments have a whole interval of closest points; the fallback takes
// the middle of their overlap, so that a side-by-side contact loads both segments
// symmetrically.
inline void closest_points(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2,
                           double& s, double& t) {
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double eps = 1e-14;
  if (a <= eps && e <= eps) {
    s = t = 0.0;
    return;
  }
  if (a <= eps) {
    s = 0.0;
    t = std::clamp(f / e, 0.0, 1.0);
    return;
  }
  const double c = d1.dot(r);
  if (e <= eps) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
    return;
  }
  const double b = d1.dot(d2);
  const double denom = a * e - b * b;
  if (denom > 1e-10 * a * e) {
    s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
  } else {
    // parallel: the ends of segment 2 projected on segment 1, middle of the overlap
    const double s0 = std::clamp(-c / a, 0.0, 1.0), s1 = std::clamp((b - c) / a, 0.0, 1.0);
    s = 0.5 * (s0 + s1);
  }
  t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1.0) {
    t = 1.0;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
}

}  // namespace slender
