// Shared test helpers: scenes built in C++, and the finite-difference check of
// forces against the energy of every conservative style.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "context.hpp"
#include "hessian.hpp"
#include "simulation.hpp"

namespace slender::test {

inline RawParams P(std::initializer_list<std::pair<const std::string, Value>> kv) {
  return RawParams(kv);
}

// A wiggly chain with random offsets so no configuration is special.
inline std::vector<Vec3> wiggly_chain(int n, int dim, unsigned seed, double amp = 0.3) {
  std::mt19937 g(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(i + u(g), u(g), dim == 3 ? u(g) : 0.0);
  return pts;
}

// A straight Cosserat rod (penalty coupling) along x: n nodes, spacing l, chain "r",
// with its stretching spring; quiet.
inline Simulation& straight_cosserat_rod(Simulation& sim, int n, double l, double GJ) {
  sim.verbose = false;
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(l * i, 0, 0);
  sim.add_chain("r", pts, 1.0, false);
  sim.add_bond("spring", P({{"k", 400.0}}));
  sim.add_bond("rod/cosserat",
               P({{"YI", 2.0}, {"GJ", GJ}, {"coupling", 50.0}, {"rot_inertia", 0.1}}));
  return sim;
}

// Compares the forces of the scene with -dE/dx by central differences, for all
// free coordinates of all nodes. Returns the worst relative error.
inline double fd_force_error(Simulation& sim, double h = 1e-6) {
  sim.compute_forces();
  auto& n = sim.nodes();
  std::vector<Vec3> f = n.f;
  double fscale = 1e-12;
  for (auto& v : f) fscale = std::max(fscale, v.cwiseAbs().maxCoeff());
  double worst = 0.0;
  const Property<int>* mask = n.find<int>("dof_mask");
  for (size_t i = 0; i < n.size(); ++i)
    for (int c = 0; c < sim.dimension(); ++c) {
      if (mask && ((*mask)[i] & (1 << c))) continue;  // clamped: no force by design
      const double x0 = n.x[i][c];
      n.x[i][c] = x0 + h;
      sim.compute_forces();
      const double ep = sim.potential_energy();
      n.x[i][c] = x0 - h;
      sim.compute_forces();
      const double em = sim.potential_energy();
      n.x[i][c] = x0;
      const double fd = -(ep - em) / (2 * h);
      worst = std::max(worst, std::abs(fd - f[i][c]) / fscale);
    }
  sim.compute_forces();
  return worst;
}

// The assembled Hessian of every force style against -df/dx by central differences, over
// the free components. Returns the worst error relative to the largest entry.
// symmetric: compare with the symmetric part of the difference quotients (a follower
// load, whose Jacobian is symmetric only up to boundary and quadrature terms)
inline double fd_hessian_error(Simulation& sim, double h = 1e-6, bool symmetric = false) {
  sim.compute_forces();  // the state the styles' Hessians read (shell ghosts placed)
  auto& n = sim.nodes();
  const int dim = sim.dimension();
  const int N = static_cast<int>(n.size());
  Hessian H;
  Context& ctx = sim.context();
  for (auto& s : sim.shells()) EXPECT_TRUE(s->add_hessian(ctx, H)) << s->style_name();
  for (auto& s : sim.bonds()) EXPECT_TRUE(s->add_hessian(ctx, H)) << s->style_name();
  for (auto& s : sim.pairs()) EXPECT_TRUE(s->add_hessian(ctx, H)) << s->style_name();
  for (auto& s : sim.fixes()) EXPECT_TRUE(s->add_hessian(ctx, H)) << s->style_name();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * N, 3 * N);
  for (const auto& t : H.triplets()) K(t.row(), t.col()) += t.value();
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(3 * N, 3 * N);
  // held components (a clamp) have no force by design: out of both
  const Property<int>* mask = n.find<int>(kHeldComponents);
  auto held = [&](int i, int c) { return mask && ((*mask)[i] & (1 << c)); };
  for (int i = 0; i < N; ++i)
    for (int c = 0; c < 3; ++c)
      if (held(i, c)) {
        K.row(3 * i + c).setZero();
        K.col(3 * i + c).setZero();
      }
  for (int j = 0; j < N; ++j)
    for (int c = 0; c < dim; ++c) {
      if (held(j, c)) continue;
      const double x0 = n.x[j][c];
      n.x[j][c] = x0 + h;
      sim.compute_forces();
      const std::vector<Vec3> fp = n.f;
      n.x[j][c] = x0 - h;
      sim.compute_forces();
      const std::vector<Vec3> fm = n.f;
      n.x[j][c] = x0;
      for (int i = 0; i < N; ++i)
        for (int r = 0; r < dim; ++r)
          if (!held(i, r)) F(3 * i + r, 3 * j + c) = -(fp[i][r] - fm[i][r]) / (2 * h);
    }
  sim.compute_forces();
  if (symmetric) F = (0.5 * (F + F.transpose())).eval();
  EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-12 * K.cwiseAbs().maxCoeff());
  return (K - F).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
}

}  // namespace slender::test
