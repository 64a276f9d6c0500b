// Newton-Raphson statics (docs/models.md §9.3): each iteration assembles the Hessian K of
// the potential energy over the free position components from every force style's exact
// second derivatives, factorises it (sparse LDL^T), solves K dx = f and takes the step
// with a backtracking line search on the energy. Where K is not positive definite (past a
// buckling load, or far from the minimum) the Newton step need not go downhill: K + mu I
// is used instead, mu grown until the factorisation has no negative pivot (Levenberg).
// The count of negative pivots of K itself is its inertia: nonzero means the state is
// not a stable equilibrium. Used by sim:minimize{method = "newton"}.
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "context.hpp"
#include "hessian.hpp"
#include "registry.hpp"
#include "simulation.hpp"

namespace slender {

class NewtonMinimizer : public IntegratorStyle {
 public:
  static ParamSpec spec(const std::string& name) {
    ParamSpec s("integrator", name,
                "Newton-Raphson minimiser of the potential energy over the node positions (for "
                "sim:minimize{method = \"newton\"}): exact Hessians of every force style, sparse "
                "LDL^T, line search, a Levenberg shift where the Hessian is not positive "
                "definite (docs/models.md §9.3); node positions only");
    declare_time_step(s, "scene time step kept for the fixes (the minimiser does not use it)");
    s.add("max_move", ParamType::RealOrAuto,
          "largest displacement of a node per iteration (length); \"auto\": unlimited")
        .def(std::string("auto"))
        .positive();
    s.output("negative_pivots",
             "negative pivots of the Hessian at the last iteration (its count of unstable "
             "directions; 0 at a stable equilibrium)");
    s.output("shift", "Levenberg shift mu added to the Hessian at the last iteration (0: none)");
    s.output("evaluations", "number of force evaluations in the iterations");
    s.output("factorizations", "number of sparse factorisations");
    return s;
  }
  NewtonMinimizer(Simulation&, const ParamValues& p)
      : max_move_(p.is_auto("max_move") ? std::numeric_limits<double>::infinity()
                                        : p.real("max_move")) {
    read_time_step(p);
  }
  double stability_limit() const override { return 2.0; }
  bool advances_time() const override { return false; }

  void setup(Simulation& sim) override {
    for (auto& c : sim.extra_coordinates())
      for (size_t i = 0; i < c->fixed->size(); ++i)
        if (!(*c->fixed)[i])
          throw InputError(
              "integrator 'newton' moves node positions only; this scene has free rod frames "
              "(generalised coordinates): use sim:minimize{method = \"fire\"}");
    for (auto& v : sim.nodes().v) v.setZero();
    if (!sim.forces_valid) sim.compute_forces();
    assemble(sim);  // names a style without a Hessian before the first step
    boost_ = 0.0;
  }

  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    const Eigen::SparseMatrix<double> K = assemble(sim);
    const long nf = K.rows();
    Eigen::VectorXd f(nf);
    for (size_t i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c)
        if (free_[3 * i + c] >= 0) f[free_[3 * i + c]] = n.f[i][c];
    // Newton step, or the Levenberg step where K is not positive definite
    double scale = 0.0;
    for (long k = 0; k < nf; ++k) scale = std::max(scale, std::abs(K.coeff(k, k)));
    if (scale == 0.0) scale = 1.0;
    Eigen::VectorXd dx;
    double mu = boost_;
    for (int tries = 0;; ++tries) {
      Eigen::SparseMatrix<double> A = K;
      if (mu > 0) {
        for (long k = 0; k < nf; ++k) A.coeffRef(k, k) += mu;
      }
      ldlt_.compute(A);
      ++factorizations_;
      long negative = 0;
      const bool ok = ldlt_.info() == Eigen::Success;
      if (ok)
        for (long k = 0; k < nf; ++k) negative += ldlt_.vectorD()[k] <= 0.0;
      if (mu == 0.0) negative_pivots_ = ok ? negative : -1;
      if (ok && negative == 0) {
        dx = ldlt_.solve(f);
        break;
      }
      if (tries > 60)
        throw InputError(
            "integrator 'newton': the Hessian stays singular however it is shifted (NaN "
            "in the state?)");
      mu = mu == 0.0 ? 1e-8 * scale : 10.0 * mu;
    }
    shift_ = mu;

    std::vector<Vec3> d(N, Vec3::Zero());
    for (size_t i = 0; i < N; ++i)
      for (int c = 0; c < 3; ++c)
        if (free_[3 * i + c] >= 0) d[i][c] = dx[free_[3 * i + c]];
    double dmax = 0.0;
    for (auto& v : d) dmax = std::max(dmax, v.norm());
    double alpha = dmax > max_move_ ? max_move_ / dmax : 1.0;
    const double slope = -f.dot(dx);  // g . d, negative
    x0_.assign(n.x.begin(), n.x.begin() + static_cast<long>(N));
    const double e0 = sim.potential_energy(), f0 = sim.max_force();
    const double c1 = 1e-4, noise = 1e-13 * std::max(std::abs(e0), 1e-300);
    bool accepted = false;
    for (int tries = 0; tries < 40 && !accepted; ++tries) {
      for (size_t i = 0; i < N; ++i) n.x[i] = x0_[i] + alpha * d[i];
      sim.compute_forces();
      ++evaluations_;
      const double e1 = sim.potential_energy();
      // Armijo; near the minimum the energy change drowns in round-off, then a step that
      // lowers the largest force is taken instead
      accepted =
          e1 <= e0 + c1 * alpha * slope || (std::abs(e1 - e0) <= noise && sim.max_force() < f0);
      if (!accepted) alpha *= 0.5;
    }
    if (!accepted) {
      // no decrease along dx: back, and a larger shift (a shorter, steeper step) next time
      for (size_t i = 0; i < N; ++i) n.x[i] = x0_[i];
      sim.compute_forces();
      ++evaluations_;
      boost_ = std::max(10.0 * shift_, 1e-6 * scale);
    } else {
      boost_ = alpha == 1.0 ? 0.0 : boost_;
    }
    sim.end_of_step();
  }

  double value(const std::string& key) const override {
    if (key == "negative_pivots") return static_cast<double>(negative_pivots_);
    if (key == "shift") return shift_;
    if (key == "evaluations") return static_cast<double>(evaluations_);
    if (key == "factorizations") return static_cast<double>(factorizations_);
    return IntegratorStyle::value(key);
  }

 private:
  // K over the free components (not held by a clamp, not z in 2D); free_[3 i + c] is the
  // row of component c of node i, or -1.
  Eigen::SparseMatrix<double> assemble(Simulation& sim) {
    H_.clear();
    Context& ctx = sim.context();
    auto add = [&](const auto& list) {
      for (const auto& s : list)
        if (!s->add_hessian(ctx, H_))
          throw InputError(
              "integrator 'newton' needs the exact Hessian of every force style, "
              "and " +
              std::string(s->family_name()) + " style '" + s->style_name() +
              "' has none: use sim:minimize{method = \"lbfgs\"} or \"fire\"");
    };
    add(sim.shells());
    add(sim.bonds());
    add(sim.pairs());
    add(sim.fixes());
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    const Property<int>* mask = n.find<int>(kHeldComponents);
    free_.assign(3 * n.size(), -1);
    int nf = 0;
    for (size_t i = 0; i < N; ++i)
      for (int c = 0; c < sim.dimension(); ++c)
        if (!mask || !((*mask)[i] & (1 << c))) free_[3 * i + c] = nf++;
    std::vector<Hessian::Triplet> t;
    t.reserve(H_.triplets().size());
    for (const auto& e : H_.triplets()) {
      const int r = free_[static_cast<size_t>(e.row())], c = free_[static_cast<size_t>(e.col())];
      if (r >= 0 && c >= 0) t.emplace_back(r, c, e.value());
    }
    Eigen::SparseMatrix<double> K(nf, nf);
    K.setFromTriplets(t.begin(), t.end());
    return K;
  }

  double max_move_;
  Hessian H_;
  std::vector<int> free_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
  std::vector<Vec3> x0_;
  double boost_ = 0.0, shift_ = 0.0;
  long negative_pivots_ = 0, evaluations_ = 0, factorizations_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "newton", slender::NewtonMinimizer)
