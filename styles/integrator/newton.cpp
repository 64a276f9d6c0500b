// Newton-Raphson statics (docs/models.md §9.3): each iteration assembles the Hessian K of
// the potential energy over the free position components from every force style's exact
// second derivatives, factorises it (sparse LDL^T), solves K dx = f and takes the step
// with a backtracking line search on the energy. Where K is not positive definite (past a
// buckling load, or far from the minimum) the Newton step need not go downhill: K + mu I
// is used instead, mu grown until the factorisation has no negative pivot (Levenberg).
// The count of negative pivots of K itself is its inertia: nonzero means the state is
// not a stable equilibrium. Used by sim:minimize{method = "newton"}.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "registry.hpp"
#include "simulation.hpp"
#include "statics.hpp"

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
    s.real("keep_factorization",
           "keep the last factorisation while an iteration cuts the largest force by at least "
           "this factor (modified Newton: a solve instead of an assembly and a factorisation; "
           "the next iteration factorises again after a slower one or a shortened step), and "
           "start each factorisation from the last Levenberg shift (negative_pivots then "
           "counts the last unshifted factorisation); 0: plain Newton, each iteration "
           "factorises the unshifted Hessian first")
        .def(0.0)
        .min(0.0)
        .max(1.0, true);
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
                                        : p.real("max_move")),
        keep_(p.real("keep_factorization")) {
    read_time_step(p);
  }
  double stability_limit() const override { return 2.0; }
  bool advances_time() const override { return false; }

  void setup(Simulation& sim) override {
    require_positions_only(sim, "integrator 'newton'");
    if (!sim.forces_valid) sim.compute_forces();
    boost_ = 0.0;
    factored_ = false;
    shift_ = 0.0;
    last_ratio_ = 1.0;
    system_ = std::make_unique<StaticSystem>(sim);
    system_->assemble();  // names a style without a Hessian before the first step
  }

  void step(Simulation& sim) override {
    auto& n = sim.nodes();
    const size_t N = n.n_owned();
    // modified Newton: the factorisation of an earlier iteration while it still converges
    // fast; its K (+ mu I) is positive definite, so its step still goes downhill
    const bool reuse = keep_ > 0 && factored_ && last_ratio_ <= keep_;
    if (!reuse) system_->assemble();
    const Eigen::VectorXd f = system_->forces();
    if (!reuse) {
      // Newton step, or the Levenberg step where K is not positive definite
      const double scale = system_->diagonal_scale();
      // with keep_factorization, from the last iteration's shift: a free body's rigid
      // motions leave K singular to round-off, and retrying mu = 0 each time costs a
      // factorisation per rung of the ladder
      // (a tenth of it, not below the ladder's first rung, so that a large shift decays)
      double mu =
          keep_ > 0 && shift_ > 0 ? std::max(boost_, std::max(0.1 * shift_, 1e-8 * scale)) : boost_;
      for (int tries = 0;; ++tries) {
        const long negative = system_->factorize(mu);
        ++factorizations_;
        if (mu == 0.0) negative_pivots_ = negative;
        if (negative == 0) break;
        if (tries > 60)
          throw InputError(
              "integrator 'newton': the Hessian stays singular however it is shifted (NaN "
              "in the state?)");
        mu = mu == 0.0 ? 1e-8 * scale : 10.0 * mu;
      }
      shift_ = mu;
      factored_ = true;
    }
    const Eigen::VectorXd dx = system_->solve(f);
    const std::vector<Vec3> d = system_->per_node(dx);
    double dmax = 0.0;
    for (size_t i = 0; i < N; ++i) dmax = std::max(dmax, d[i].norm());
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
      boost_ = std::max(10.0 * shift_, 1e-6 * system_->diagonal_scale());
      factored_ = false;
    } else {
      if (!reuse) boost_ = alpha == 1.0 ? 0.0 : boost_;
      // a full step that cut the force enough keeps the factorisation for the next one
      last_ratio_ = alpha == 1.0 && f0 > 0 ? sim.max_force() / f0 : 1.0;
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
  double max_move_, keep_;
  std::unique_ptr<StaticSystem> system_;
  bool factored_ = false;
  double last_ratio_ = 1.0;
  std::vector<Vec3> x0_;
  double boost_ = 0.0, shift_ = 0.0;
  long negative_pivots_ = 0, evaluations_ = 0, factorizations_ = 0;
};

}  // namespace slender

SLENDER_REGISTER_STYLE(slender::IntegratorStyle, "newton", slender::NewtonMinimizer)
