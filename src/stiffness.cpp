#include "stiffness.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "simulation.hpp"

namespace slender {

namespace {

// A degree of freedom: a node component (frame < 0), or a tangent direction w of the
// frame quaternion of node `node` in coordinate family `frame`.
struct Dof {
  int frame = -1;
  size_t node = 0;
  int comp = 0;
  Vec4 w = Vec4::Zero();
};

// Orthonormal basis of the tangent space of the unit sphere at q (Gram-Schmidt).
std::vector<Vec4> tangent_basis(const Vec4& q) {
  std::vector<Vec4> out;
  for (int k = 0; k < 4 && out.size() < 3; ++k) {
    Vec4 w = Vec4::Unit(k);
    w -= w.dot(q) * q;
    for (auto& b : out) w -= w.dot(b) * b;
    if (w.norm() > 1e-6) out.push_back(w.normalized());
  }
  return out;
}

}  // namespace

StiffnessResult lowest_stiffness(Simulation& sim, double eps) {
  auto& n = sim.nodes();
  const size_t N = n.n_owned();
  const int dim = sim.dimension();
  sim.compute_forces();  // binds the styles and their frames
  std::vector<Dof> dofs;
  const auto* mask = n.find<int>(kHeldComponents);  // components held by clamps
  for (size_t i = 0; i < N; ++i)
    for (int c = 0; c < dim; ++c)
      if (!mask || !((*mask)[i] & (1 << c))) dofs.push_back(Dof{-1, i, c, Vec4::Zero()});
  auto& cs = sim.extra_coordinates();
  for (size_t s = 0; s < cs.size(); ++s)
    for (size_t i = 0; i < N; ++i) {
      if ((*cs[s]->fixed)[i]) continue;
      for (auto& w : tangent_basis((*cs[s]->q)[i]))
        dofs.push_back(Dof{static_cast<int>(s), i, 0, w});
    }
  const size_t m = dofs.size();
  auto forces = [&](Eigen::VectorXd& out) {
    sim.compute_forces();
    out.resize(static_cast<Eigen::Index>(m));
    for (size_t k = 0; k < m; ++k) {
      const Dof& d = dofs[k];
      out(static_cast<Eigen::Index>(k)) =
          d.frame < 0 ? n.f[d.node](d.comp)
                      : (*cs[static_cast<size_t>(d.frame)]->f)[d.node].dot(d.w);
    }
  };
  auto move = [&](const Dof& d, double h) {
    if (d.frame < 0) {
      n.x[d.node](d.comp) += h;
    } else {
      Vec4& q = (*cs[static_cast<size_t>(d.frame)]->q)[d.node];
      q = (q + h * d.w).normalized();
    }
  };
  Eigen::MatrixXd H(m, m);
  Eigen::VectorXd fp, fm;
  for (size_t j = 0; j < m; ++j) {
    const Dof& d = dofs[j];
    const Vec3 x0 = n.x[d.node];
    const Vec4 q0 = d.frame < 0 ? Vec4::Zero() : (*cs[static_cast<size_t>(d.frame)]->q)[d.node];
    auto restore = [&] {
      if (d.frame < 0)
        n.x[d.node] = x0;
      else
        (*cs[static_cast<size_t>(d.frame)]->q)[d.node] = q0;
    };
    move(d, eps);
    forces(fp);
    restore();
    move(d, -eps);
    forces(fm);
    restore();
    H.col(static_cast<Eigen::Index>(j)) = -(fp - fm) / (2.0 * eps);
  }
  sim.compute_forces();
  // a held degree of freedom (its force is zeroed) has an empty row: drop it
  const double scale = H.cwiseAbs().maxCoeff();
  std::vector<Eigen::Index> keep;
  for (Eigen::Index r = 0; r < H.rows(); ++r)
    if (H.row(r).cwiseAbs().maxCoeff() > 1e-12 * scale) keep.push_back(r);
  Eigen::MatrixXd K(keep.size(), keep.size());
  for (size_t a = 0; a < keep.size(); ++a)
    for (size_t b = 0; b < keep.size(); ++b)
      K(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) =
          0.5 * (H(keep[a], keep[b]) + H(keep[b], keep[a]));
  StiffnessResult r;
  r.dofs = static_cast<int>(keep.size());
  if (keep.empty()) return r;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(K, Eigen::EigenvaluesOnly);
  r.lowest = es.eigenvalues()(0);
  return r;
}

}  // namespace slender
