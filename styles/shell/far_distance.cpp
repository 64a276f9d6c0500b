// The smallest distance between parts of a shell that lie far apart in the reference (the
// wings of an e-cone, not its apex), measured between the mid-surface facets of the control
// mesh, as the shell contact measures (docs/models.md §6.10): the "kiss" of two wings can
// then be taken both ways, when this distance reaches the contact thickness h or when the
// mid-surfaces themselves touch (distance 0, in a run without self-contact). Two facets
// that pierce each other are at distance 0 (an edge crossing a face), so a run whose wings
// pass through each other reads 0, not the distance of their far edges. Pairs farther than
// `reach` apart are not searched: the distance then reads `reach` (a lower bound).
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cell_grid.hpp"
#include "registry.hpp"
#include "shell/triangle_distance.hpp"
#include "shell/trimesh.hpp"
#include "simulation.hpp"

namespace slender {

class FarDistanceCompute : public ComputeStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("compute", name,
                "smallest distance between the mid-surface facets of parts of a shell that lie "
                "far apart in the reference (e-cone wings: the kiss by mid-surfaces)");
    s.string("mesh", "surface created by sim:mesh").required();
    s.real("far_distance",
           "two facets count when their closest reference vertices are farther apart than "
           "this (as contact/shell's far_distance)")
        .required()
        .positive();
    s.real("reach", "pairs are searched up to this distance; farther, distance reads reach")
        .required()
        .positive();
    s.output("distance", "the smallest distance between far facets (reach if none is nearer)");
    s.output("x", "x of the midpoint of the closest far pair (0 if none within reach)");
    s.output("y", "y of that midpoint");
    s.output("z", "z of that midpoint");
    return s;
  }
  FarDistanceCompute(Simulation& sim, const ParamValues& p)
      : far_(p.real("far_distance")), reach_(p.real("reach")) {
    const Surface* s = sim.topology().find_surface(p.str("mesh"));
    if (!s) throw InputError("compute 'far_distance': no mesh named '" + p.str("mesh") + "'");
    mesh_ = s->mesh;
    base_ = s->first_node;
  }

  void evaluate(Simulation& sim) override {
    const auto& g = *mesh_;
    const auto& x = sim.nodes().x;
    const int nt = g.n_real_tris;
    std::vector<Vec3> centre(static_cast<size_t>(nt));
    double radius = 0;  // the largest distance from a facet's centroid to its corners
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (int t = 0; t < nt; ++t) {
      const auto& tr = g.mesh.tri[t];
      const Vec3 c = (x[base_ + tr[0]] + x[base_ + tr[1]] + x[base_ + tr[2]]) / 3.0;
      centre[static_cast<size_t>(t)] = c;
      for (int k = 0; k < 3; ++k) radius = std::max(radius, (x[base_ + tr[k]] - c).norm());
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
    // two facets within reach have centroids within reach + 2 radius
    const double cell = reach_ + 2 * radius;
    grid_.build(lo, hi, cell, 3, centre);
    distance_ = reach_;
    where_.setZero();
    const double far2 = far_ * far_;
    for (int a = 0; a < nt; ++a) {
      const auto& ta = g.mesh.tri[a];
      const std::array<Vec3, 3> A = {x[base_ + ta[0]], x[base_ + ta[1]], x[base_ + ta[2]]};
      grid_.for_each_near_above(centre[static_cast<size_t>(a)], a, [&](int b) {
        const auto& tb = g.mesh.tri[b];
        if ((centre[static_cast<size_t>(b)] - centre[static_cast<size_t>(a)]).norm() >
            distance_ + 2 * radius)
          return;
        for (int i = 0; i < 3; ++i)  // near in the reference: not a far pair
          for (int j = 0; j < 3; ++j)
            if ((g.mesh.x[ta[i]] - g.mesh.x[tb[j]]).squaredNorm() <= far2) return;
        const std::array<Vec3, 3> B = {x[base_ + tb[0]], x[base_ + tb[1]], x[base_ + tb[2]]};
        double d;
        Vec3 mid;
        if (pierce(A, B, &mid) || pierce(B, A, &mid)) {
          d = 0;
        } else {
          const shell::TrianglePair tp = shell::triangle_distance(A, B);
          d = tp.dist;
          const Vec3 pa = tp.w1[0] * A[0] + tp.w1[1] * A[1] + tp.w1[2] * A[2];
          mid = pa - 0.5 * tp.d;
        }
        if (d < distance_) {
          distance_ = d;
          where_ = mid;
        }
      });
    }
  }
  double value(const std::string& key) const override {
    if (key == "distance") return distance_;
    if (key.size() == 1 && key[0] >= 'x' && key[0] <= 'z') return where_[key[0] - 'x'];
    return ComputeStyle::value(key);
  }

 private:
  // whether an edge of A crosses the face of B (Moller–Trumbore), and where
  static bool pierce(const std::array<Vec3, 3>& A, const std::array<Vec3, 3>& B, Vec3* at) {
    const Vec3 e1 = B[1] - B[0], e2 = B[2] - B[0];
    for (int i = 0; i < 3; ++i) {
      const Vec3 p = A[i], dir = A[(i + 1) % 3] - A[i];
      const Vec3 h = dir.cross(e2);
      const double det = e1.dot(h);
      if (std::abs(det) < 1e-300) continue;  // parallel to the face
      const Vec3 s = p - B[0];
      const double u = s.dot(h) / det;
      if (u < 0 || u > 1) continue;
      const Vec3 q = s.cross(e1);
      const double v = dir.dot(q) / det;
      if (v < 0 || u + v > 1) continue;
      const double t = e2.dot(q) / det;
      if (t < 0 || t > 1) continue;
      *at = p + t * dir;
      return true;
    }
    return false;
  }

  double far_, reach_;
  std::shared_ptr<const shell::GhostedMesh> mesh_;
  int base_ = 0;
  CellGrid grid_;
  double distance_ = 0;
  Vec3 where_ = Vec3::Zero();
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::ComputeStyle, "far_distance", slender::FarDistanceCompute)
