// The Hessian of a contact energy E(r) of the distance r between two closest points
// (docs/models.md §9.9), shared by the pair styles. Each closest point is an affine
// combination of nodes whose weights are affine in the parameters p that place it on its
// feature (the position along a segment); r_vec = sum_k c_k(p) x_k. A parameter inside
// its feature makes D = |r_vec|^2 stationary, so the distance is the envelope over the
// free parameters and its Hessian is the Schur complement
//   H_D = D_xx - D_xp D_pp^+ D_px,  D_xx = 2 c c^T (x) I,  D_{x_k p_m} = 2 (dc_km r + c_k g_m),
//   D_{p_m p_n} = 2 g_m . g_n,  g_m = sum_k dc_km x_k;
// a parameter held at an end of its feature is a constant. With r = sqrt(D):
//   grad r = grad D / 2r,  hess r = H_D / 2r - grad D grad D^T / 4 r^3,
//   hess E = E''(r) grad r grad r^T + E'(r) hess r.
// (The pseudo-inverse serves parallel segments, whose closest points form an interval.)
#pragma once

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "hessian.hpp"
#include "nodes.hpp"

namespace slender {

// K nodes, P free parameters (0..2); dc is K x P (each column: d c / d p_m).
// dE, d2E: E'(r) and E''(r). Adds the dim x dim blocks (2D: the plane's).
template <int K>
void add_distance_hessian(Hessian& H, const std::array<int, K>& node, const std::vector<Vec3>& x,
                          const Eigen::Matrix<double, K, 1>& c, const Eigen::MatrixXd& dc,
                          double dE, double d2E, int dim) {
  constexpr int N = 3 * K;
  std::array<double, 3> r{};
  for (int k = 0; k < K; ++k)
    for (int q = 0; q < 3; ++q) r[q] += c[k] * x[static_cast<std::size_t>(node[k])][q];
  const double D = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
  if (!(D > 0.0)) return;
  const double rl = std::sqrt(D);
  Eigen::Matrix<double, N, 1> gD;
  Eigen::Matrix<double, N, N> HD = Eigen::Matrix<double, N, N>::Zero();
  // (element by element: g++ 12 warns about Eigen's AVX copies of a Vec3 into blocks)
  for (int k = 0; k < K; ++k)
    for (int q = 0; q < 3; ++q) {
      gD[3 * k + q] = 2.0 * c[k] * r[q];
      for (int l = 0; l < K; ++l) HD(3 * k + q, 3 * l + q) = 2.0 * c[k] * c[l];
    }
  const int P = static_cast<int>(dc.cols());
  if (P > 0) {
    Eigen::MatrixXd g(3, P), B(N, P), Dpp(P, P);
    for (int m = 0; m < P; ++m)
      for (int q = 0; q < 3; ++q) {
        double gq = 0.0;
        for (int k = 0; k < K; ++k) gq += dc(k, m) * x[static_cast<std::size_t>(node[k])][q];
        g(q, m) = gq;
      }
    for (int m = 0; m < P; ++m) {
      for (int k = 0; k < K; ++k)
        for (int q = 0; q < 3; ++q) B(3 * k + q, m) = 2.0 * (dc(k, m) * r[q] + c[k] * g(q, m));
      for (int n = 0; n < P; ++n) Dpp(m, n) = 2.0 * g.col(m).dot(g.col(n));
    }
    const Eigen::MatrixXd inv = Dpp.completeOrthogonalDecomposition().pseudoInverse();
    HD -= B * inv * B.transpose();
  }
  const Eigen::Matrix<double, N, 1> gr = gD / (2.0 * rl);
  const Eigen::Matrix<double, N, N> hr = HD / (2.0 * rl) - gD * gD.transpose() / (4.0 * D * rl);
  const Eigen::Matrix<double, N, N> HE = d2E * gr * gr.transpose() + dE * hr;
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < K; ++l) {
      if (dim == 2)
        H.add(node[k], node[l], Eigen::Matrix2d(HE.template block<2, 2>(3 * k, 3 * l)));
      else
        H.add(node[k], node[l], Eigen::Matrix3d(HE.template block<3, 3>(3 * k, 3 * l)));
    }
}

}  // namespace slender
