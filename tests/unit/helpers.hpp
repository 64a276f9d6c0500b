// Shared test helpers: scenes built in C++, and the finite-difference check of
// forces against the energy of every conservative style.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

}  // namespace slender::test
