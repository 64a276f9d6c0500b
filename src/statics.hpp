// The static system of a scene over its free position components (docs/models.md §9): the
// Hessian K of the potential energy, assembled from every force style's exact second
// derivatives, its sparse LDL^T factorisation and inertia, and the forces as a vector.
// Shared by the Newton minimiser (styles/integrator/newton.cpp) and continuation
// (src/continuation.cpp).
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <string>
#include <vector>

#include "hessian.hpp"
#include "nodes.hpp"

namespace slender {

class Simulation;

// Refuses a scene with free rod frames (generalised coordinates) for a solver that moves the
// node positions only; `who` names the solver in the message. Also puts the nodes at rest.
void require_positions_only(Simulation& sim, const std::string& who);

class StaticSystem {
 public:
  explicit StaticSystem(Simulation& sim) : sim_(sim) {}
  // K at the current state over the components that are free now (not held by a clamp or a
  // driven node, not z in 2D). Throws InputError naming the first force style that has no
  // Hessian.
  const Eigen::SparseMatrix<double>& assemble();
  const Eigen::SparseMatrix<double>& matrix() const { return K_; }
  long size() const { return K_.rows(); }
  // Factorises K + mu I. Returns its count of negative pivots (0 where positive
  // definite), or -1 where the factorisation met a zero pivot.
  long factorize(double mu = 0.0);
  // (K + mu I)^{-1} r with the last factorisation
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const { return ldlt_.solve(r); }
  // The nodal forces of the last evaluation on the free components.
  Eigen::VectorXd forces() const;
  // A per-node vector's free components.
  Eigen::VectorXd gather(const std::vector<Vec3>& v) const;
  // A vector over the free components as one displacement per node (held ones 0).
  std::vector<Vec3> per_node(const Eigen::VectorXd& v) const;
  // The largest |K_ii| (a scale for shifts).
  double diagonal_scale() const;
  // The Levenberg shift of the last positive definite factorisation a minimiser settled on
  // (0: none); the next minimisation's ladder starts from a tenth of it.
  double last_shift() const { return last_shift_; }
  void set_last_shift(double mu) { last_shift_ = mu; }

 private:
  // free[3 i + c]: the row of component c of node i, or -1; returns the count
  int free_components(std::vector<int>& free) const;

  Simulation& sim_;
  Hessian H_;
  std::vector<int> free_;  // row of component c of node i at 3 i + c, or -1
  Eigen::SparseMatrix<double> K_, shifted_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  // The assembly's entries (column << 32 | row, in the styles' order) and values; the
  // entries of the last new pattern, where each one lands in K_'s values, and the
  // diagonal's places. An assembly with the pattern of the last one only adds values.
  std::vector<std::uint64_t> keys_, pattern_;
  std::vector<double> values_;
  std::vector<int> slot_, diagonal_;
  long pattern_version_ = 0, analyzed_version_ = -1;
  double last_shift_ = 0.0;
};

}  // namespace slender
