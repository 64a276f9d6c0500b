#include "statics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
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

int StaticSystem::free_components(std::vector<int>& free) const {
  auto& n = sim_.nodes();
  const size_t N = n.n_owned();
  const Property<int>* mask = n.find<int>(kHeldComponents);
  free.assign(3 * n.size(), -1);
  int nf = 0;
  for (size_t i = 0; i < N; ++i)
    for (int c = 0; c < sim_.dimension(); ++c)
      if (!mask || !((*mask)[i] & (1 << c))) free[3 * i + c] = nf++;
  return nf;
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
  const int nf = free_components(free_);
  // this assembly's entries over the free components, and an explicit diagonal (so that a
  // shift K + mu I never adds an entry)
  keys_.clear();
  values_.clear();
  for (const auto& e : H_.triplets()) {
    const int r = free_[static_cast<size_t>(e.row())], c = free_[static_cast<size_t>(e.col())];
    if (r >= 0 && c >= 0) {
      keys_.push_back((static_cast<std::uint64_t>(static_cast<unsigned>(c)) << 32) |
                      static_cast<unsigned>(r));
      values_.push_back(e.value());
    }
  }
  for (int k = 0; k < nf; ++k) {
    keys_.push_back((static_cast<std::uint64_t>(static_cast<unsigned>(k)) << 32) |
                    static_cast<unsigned>(k));
    values_.push_back(0.0);
  }
  if (nf == K_.rows() && keys_ == pattern_) {
    // the same entries in the same order as the last assembly (the usual case between
    // Newton iterations): add the values into the kept matrix in the order setFromTriplets
    // sums them, with no sort and no allocation
    double* v = K_.valuePtr();
    std::fill(v, v + K_.nonZeros(), 0.0);
    for (size_t k = 0; k < values_.size(); ++k) v[slot_[k]] += values_[k];
    return K_;
  }
  std::vector<Hessian::Triplet> t;
  t.reserve(keys_.size());
  for (size_t k = 0; k < keys_.size(); ++k)
    t.emplace_back(static_cast<int>(keys_[k] & 0xffffffffu), static_cast<int>(keys_[k] >> 32),
                   values_[k]);
  K_.resize(nf, nf);
  K_.setFromTriplets(t.begin(), t.end());
  K_.makeCompressed();
  // where each entry landed (column-major, rows sorted within a column)
  slot_.resize(keys_.size());
  const int* outer = K_.outerIndexPtr();
  const int* inner = K_.innerIndexPtr();
  for (size_t k = 0; k < keys_.size(); ++k) {
    const int r = static_cast<int>(keys_[k] & 0xffffffffu), c = static_cast<int>(keys_[k] >> 32);
    slot_[k] =
        static_cast<int>(std::lower_bound(inner + outer[c], inner + outer[c + 1], r) - inner);
  }
  diagonal_.resize(static_cast<size_t>(nf));
  for (int k = 0; k < nf; ++k) diagonal_[static_cast<size_t>(k)] = slot_[keys_.size() - nf + k];
  pattern_.swap(keys_);
  ++pattern_version_;
  return K_;
}

long StaticSystem::factorize(double mu) {
  // the symbolic analysis (ordering, elimination tree) depends on the pattern only
  if (analyzed_version_ != pattern_version_) {
    ldlt_.analyzePattern(K_);
    analyzed_version_ = pattern_version_;
  }
  if (mu > 0) {
    shifted_ = K_;
    for (const int d : diagonal_) shifted_.valuePtr()[d] += mu;
    ldlt_.factorize(shifted_);
  } else {
    ldlt_.factorize(K_);
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
  return gather(sim_.nodes().f);
}

Eigen::VectorXd StaticSystem::gather(const std::vector<Vec3>& v) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(K_.rows());
  for (size_t k = 0; k < free_.size() && k / 3 < v.size(); ++k)
    if (free_[k] >= 0) out[free_[k]] = v[k / 3][static_cast<int>(k % 3)];
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
