#include "statics.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "context.hpp"
#include "simulation.hpp"

namespace slender {

void require_positions_only(Simulation& sim, const std::string& who) {
  for (auto& c : sim.extra_coordinates())
    for (size_t i = 0; i < c->fixed->size(); ++i)
      if (!(*c->fixed)[i])
        throw InputError(who +
                         " moves node positions only; this scene has free rod frames "
                         "(generalised coordinates): use sim:minimize{method = \"fire\"}");
  for (auto& v : sim.nodes().v) v.setZero();
}

const Eigen::SparseMatrix<double>& StaticSystem::assemble() {
  H_.clear();
  Context& ctx = sim_.context();
  auto add = [&](const auto& list) {
    for (const auto& s : list)
      if (!s->add_hessian(ctx, H_))
        throw InputError(std::string("statics need the exact Hessian of every force style, and ")
                             .append(s->family_name())
                             .append(" style '")
                             .append(s->style_name())
                             .append("' has none: use sim:minimize{method = \"lbfgs\"} or "
                                     "\"fire\""));
  };
  add(sim_.shells());
  add(sim_.bonds());
  add(sim_.pairs());
  add(sim_.fixes());
  auto& n = sim_.nodes();
  const size_t N = n.n_owned();
  const Property<int>* mask = n.find<int>(kHeldComponents);
  free_.assign(3 * n.size(), -1);
  int nf = 0;
  for (size_t i = 0; i < N; ++i)
    for (int c = 0; c < sim_.dimension(); ++c)
      if (!mask || !((*mask)[i] & (1 << c))) free_[3 * i + c] = nf++;
  std::vector<Hessian::Triplet> t;
  t.reserve(H_.triplets().size());
  for (const auto& e : H_.triplets()) {
    const int r = free_[static_cast<size_t>(e.row())], c = free_[static_cast<size_t>(e.col())];
    if (r >= 0 && c >= 0) t.emplace_back(r, c, e.value());
  }
  K_.resize(nf, nf);
  K_.setFromTriplets(t.begin(), t.end());
  return K_;
}

long StaticSystem::factorize(double mu) {
  if (mu > 0) {
    Eigen::SparseMatrix<double> A = K_;
    for (long k = 0; k < A.rows(); ++k) A.coeffRef(k, k) += mu;
    ldlt_.compute(A);
  } else {
    ldlt_.compute(K_);
  }
  if (ldlt_.info() != Eigen::Success) return -1;
  long negative = 0;
  for (long k = 0; k < K_.rows(); ++k) {
    const double d = ldlt_.vectorD()[k];
    if (!(d > 0.0)) {
      if (d == 0.0 || !std::isfinite(d)) return -1;
      ++negative;
    }
  }
  return negative;
}

Eigen::VectorXd StaticSystem::forces() const {
  const auto& f = sim_.nodes().f;
  Eigen::VectorXd out(K_.rows());
  for (size_t k = 0; k < free_.size(); ++k)
    if (free_[k] >= 0) out[free_[k]] = f[k / 3][static_cast<int>(k % 3)];
  return out;
}

std::vector<Vec3> StaticSystem::per_node(const Eigen::VectorXd& v) const {
  std::vector<Vec3> d(free_.size() / 3, Vec3::Zero());
  for (size_t k = 0; k < free_.size(); ++k)
    if (free_[k] >= 0) d[k / 3][static_cast<int>(k % 3)] = v[free_[k]];
  return d;
}

double StaticSystem::diagonal_scale() const {
  double s = 0.0;
  for (long k = 0; k < K_.rows(); ++k) s = std::max(s, std::abs(K_.coeff(k, k)));
  return s > 0.0 ? s : 1.0;
}

}  // namespace slender
