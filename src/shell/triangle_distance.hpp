// Closest points of two triangles of the faceted control mesh (docs/models.md §6.10,
// dense phase): the minimum over the 6 vertex-triangle and 9 edge-edge distances,
// which is the triangle-triangle distance whenever the two do not intersect.
#pragma once

#include <array>
#include <cmath>

#include "nodes.hpp"
#include "segment_geometry.hpp"

namespace slender::shell {

// Closest point of triangle (a, b, c) to p, as barycentric weights (wa, wb, wc),
// by the Voronoi regions of the vertices, edges and face.
inline std::array<double, 3> closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                                 const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

struct TrianglePair {
  double dist = 1e300;
  Vec3 d = Vec3::Zero();             // closest point on T1 minus closest point on T2
  std::array<double, 3> w1{}, w2{};  // barycentric weights on T1 and T2
};

// Calls f(TrianglePair) for each of the 6 vertex-triangle and 9 edge-edge closest-point
// problems of two triangles. Masks select features (vertex k / edge k->k+1 of each
// triangle) so that a caller summing over many triangle pairs counts each once.
struct FeatureMask {
  std::array<bool, 3> vertex{true, true, true}, edge{true, true, true};
};
template <class F>
void for_each_feature_pair(const std::array<Vec3, 3>& A, const std::array<Vec3, 3>& B, F&& f,
                           const FeatureMask& ma = {}, const FeatureMask& mb = {}) {
  auto take = [&](const Vec3& p1, const Vec3& p2, const std::array<double, 3>& w1,
                  const std::array<double, 3>& w2) {
    TrianglePair tp;
    tp.d = p1 - p2;
    tp.dist = tp.d.norm();
    tp.w1 = w1;
    tp.w2 = w2;
    f(tp);
  };
  for (int k = 0; k < 3; ++k) {
    if (ma.vertex[k]) {
      auto wb = closest_on_triangle(A[k], B[0], B[1], B[2]);
      std::array<double, 3> wa{};
      wa[k] = 1;
      take(A[k], wb[0] * B[0] + wb[1] * B[1] + wb[2] * B[2], wa, wb);
    }
    if (mb.vertex[k]) {
      auto wa2 = closest_on_triangle(B[k], A[0], A[1], A[2]);
      std::array<double, 3> wbk{};
      wbk[k] = 1;
      take(wa2[0] * A[0] + wa2[1] * A[1] + wa2[2] * A[2], B[k], wa2, wbk);
    }
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (!ma.edge[i] || !mb.edge[j]) continue;
      const int i2 = (i + 1) % 3, j2 = (j + 1) % 3;
      double s = 0, t = 0;
      closest_points(A[i], A[i2], B[j], B[j2], s, t);
      std::array<double, 3> wa{}, wb{};
      wa[i] = 1 - s;
      wa[i2] = s;
      wb[j] = 1 - t;
      wb[j2] = t;
      take(A[i] + s * (A[i2] - A[i]), B[j] + t * (B[j2] - B[j]), wa, wb);
    }
}

inline TrianglePair triangle_distance(const std::array<Vec3, 3>& A, const std::array<Vec3, 3>& B) {
  TrianglePair best;
  for_each_feature_pair(A, B, [&](const TrianglePair& tp) {
    if (tp.dist < best.dist) best = tp;
  });
  return best;
}

}  // namespace slender::shell
