// The Hessian of the potential energy over the node positions (docs/models.md §9), for
// Newton statics: each force style adds its second derivatives as 3x3 blocks between
// nodes; rows and columns are position components, node * 3 + component (the z rows of a
// 2D scene are left empty and dropped by the solver with the held components).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "nodes.hpp"

namespace slender {

class Hessian {
 public:
  using Triplet = Eigen::Triplet<double>;
  // d^2E / dx_i dx_j as a block; add (i, j) and (j, i) separately, or use add_pair.
  void add(int i, int j, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (b(r, c) != 0.0) t_.emplace_back(3 * i + r, 3 * j + c, b(r, c));
  }
  void add(int i, int j, const Eigen::Matrix2d& b) {
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c)
        if (b(r, c) != 0.0) t_.emplace_back(3 * i + r, 3 * j + c, b(r, c));
  }
  // the blocks (i, j) = b and (j, i) = b^T of a pair i != j
  template <class M>
  void add_pair(int i, int j, const M& b) {
    add(i, j, b);
    add(j, i, M(b.transpose()));
  }
  const std::vector<Triplet>& triplets() const { return t_; }
  void clear() { t_.clear(); }

 private:
  std::vector<Triplet> t_;
};

}  // namespace slender
